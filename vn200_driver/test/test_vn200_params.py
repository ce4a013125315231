"""The vn200 node refuses a bad parameter at start, names it, and exits with status 2
(instead of configuring the sensor with something it cannot do), and accepts every rate the
VN-200 offers, 128000 included. Runs the built node against a private rosmaster on a free
loopback port; DRONE_ROS_WS points at the catkin workspace."""
import fcntl
import os
import select
import struct
import subprocess
import time

import pytest
from stack_testing.ros_master import private_master


@pytest.fixture(scope="module")
def ros_env():
    ws = os.environ.get("DRONE_ROS_WS")
    assert ws, "DRONE_ROS_WS must point at the catkin workspace (tools/run_tests.sh sets it)"
    exe = os.path.join(ws, "devel", "lib", "drone_ros", "vn200")
    assert os.access(exe, os.X_OK), exe + " not built"
    with private_master(log_dir=os.path.join(ws, "..", "vn200_test_logs")) as env:
        yield exe, env


@pytest.mark.parametrize("arg, named", [
    ("_rate_hz:=300", "~rate_hz"),             # 800 Hz / 300 is not an integer divisor
    ("_baud:=100000", "~baud"),                # not a rate the VN-200 offers
    ("_sensor_port:=3", "~sensor_port"),       # the VN-200 has ports 1 and 2
    ("_binary_output:=4", "~binary_output"),   # the VN-200 has binary outputs 1..3
    ("_binary_output:=1", "the HA's"),         # register 75 feeds the HA's port 1: not the HP's
    ("_rate_hz:=800", "needs more than ~baud"),  # 800 x 176-byte packets exceed 921600 baud
    ("_data_timeout_s:=0", "~data_timeout_s"),
    ("_sensor_baud:=1234", "~sensor_baud"),
])
def test_bad_parameter_is_refused_at_start_and_named(ros_env, arg, named):
    exe, env = ros_env
    # A node name of its own per case: private parameters stay on the master between runs.
    name = "vn200_params_" + "".join(c for c in arg if c.isalnum())
    r = subprocess.run([exe, "__name:=" + name, arg], env=env, capture_output=True,
                       text=True, timeout=30)
    assert r.returncode == 2, r.stdout + r.stderr
    assert named in r.stdout + r.stderr


def _tty_output_baud(fd):
    """The speed a tty really runs at, read through termios2 (TCGETS2), which also reports rates
    termios has no constant for. struct termios2 is 44 bytes with c_ospeed last on x86-64 and
    arm64 (asm-generic)."""
    tcgets2 = (2 << 30) | (44 << 16) | (ord("T") << 8) | 0x2A
    raw = fcntl.ioctl(fd, tcgets2, bytes(44))
    return struct.unpack_from("I", raw, 40)[0]


def test_vn200s_128000_baud_is_accepted_and_the_port_runs_at_it(ros_env):
    # termios has no constant for 128000, so the node used to refuse it; the shared serial port
    # sets it through termios2. 50 Hz fits in 128000 baud (100 Hz would not).
    exe, env = ros_env
    master, slave = os.openpty()
    node = subprocess.Popen([exe, "__name:=vn200_params_baud128000", "_baud:=128000",
                             "_rate_hz:=50", "_port:=" + os.ttyname(slave)], env=env,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        heard = b""
        deadline = time.monotonic() + 20
        while b"$VN" not in heard and node.poll() is None and time.monotonic() < deadline:
            if select.select([master], [], [], 0.2)[0]:
                heard += os.read(master, 256)
        assert node.poll() is None, "node exited with %s" % node.returncode
        assert b"$VN" in heard, "the node never configured the sensor"
        assert _tty_output_baud(slave) == 128000
    finally:
        node.terminate()
        node.wait(timeout=10)
        os.close(master)
        os.close(slave)
