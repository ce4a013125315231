"""The vn200 node refuses a bad parameter at start, names it, and exits with status 2
(instead of configuring the sensor with something it cannot do). Runs the built node against a
private rosmaster on a free loopback port; DRONE_ROS_WS points at the catkin workspace."""
import os
import socket
import subprocess
import time

import pytest


def _free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.fixture(scope="module")
def ros_env():
    ws = os.environ.get("DRONE_ROS_WS")
    assert ws, "DRONE_ROS_WS must point at the catkin workspace (tools/run_tests.sh sets it)"
    exe = os.path.join(ws, "devel", "lib", "drone_ros", "vn200")
    assert os.access(exe, os.X_OK), exe + " not built"
    port = _free_port()
    env = dict(os.environ, ROS_MASTER_URI="http://127.0.0.1:%d" % port, ROS_IP="127.0.0.1",
               ROS_HOSTNAME="127.0.0.1", ROS_LOG_DIR=os.path.join(ws, "..", "vn200_test_logs"))
    master = subprocess.Popen(["rosmaster", "--core", "-p", str(port)], env=env,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 20
        while True:
            try:
                socket.create_connection(("127.0.0.1", port), timeout=0.5).close()
                break
            except OSError:
                assert time.monotonic() < deadline, "rosmaster did not start"
                time.sleep(0.1)
        yield exe, env
    finally:
        master.terminate()
        master.wait(timeout=10)


@pytest.mark.parametrize("arg, named", [
    ("_rate_hz:=300", "~rate_hz"),             # 800 Hz / 300 is not an integer divisor
    ("_baud:=100000", "~baud"),                # not a rate the VN-200 offers
    ("_sensor_port:=3", "~sensor_port"),       # the VN-200 has ports 1 and 2
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
