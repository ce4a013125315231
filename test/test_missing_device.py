"""Starting a node whose serial device is missing or not a serial port, as a user does with the
wrong port or the adapter unplugged: the log names the port and the fix (the /dev/serial/by-id/
path), never a stack trace, and the node keeps trying, so a device plugged in late is found.
(Permission denied and its dialout-group fix: drone_ros/common's test_serial_port.)"""
import os
import subprocess
import threading
import time

import pytest


def node_log_until(env, node, args, wanted, timeout_s=30.0):
    """Runs the built node, collects its output until every string in wanted has appeared (or the
    time is up), and returns (output, still_running)."""
    exe = os.path.join(os.environ["DRONE_ROS_WS"], "devel", "lib", "drone_ros", node)
    proc = subprocess.Popen([exe] + args, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            start_new_session=True)
    out = []
    reader = threading.Thread(target=lambda: out.extend(iter(proc.stdout.readline, b"")), daemon=True)
    reader.start()
    try:
        deadline = time.time() + timeout_s
        while time.time() < deadline and not all(w in b"".join(out).decode(errors="replace") for w in wanted):
            time.sleep(0.1)
        running = proc.poll() is None
    finally:
        proc.kill()
        proc.wait()
        reader.join(timeout=5)
    return b"".join(out).decode(errors="replace"), running


@pytest.mark.parametrize("node,param", [("vn200", "_port"), ("arduino", "_port")])
def test_a_missing_device_names_the_port_and_the_by_id_path_and_keeps_trying(master, node, param):
    path = "/dev/ttyUSB_unplugged_%s" % node
    text, running = node_log_until(master, node, ["%s:=%s" % (param, path), "__name:=%s_test" % node],
                                   [path, "/dev/serial/by-id/"])
    assert path in text and "No such file or directory" in text, text
    assert "plugged in" in text and "/dev/serial/by-id/" in text, text
    assert "Traceback" not in text and "terminate called" not in text, text
    assert running, "the node gave up instead of waiting for the device:\n" + text


@pytest.mark.parametrize("node,param", [("vn200", "_port"), ("arduino", "_port")])
def test_a_path_that_is_no_serial_device_is_named_as_such(master, node, param):
    text, running = node_log_until(master, node, ["%s:=/dev/null" % param, "__name:=%s_test" % node],
                                   ["/dev/null", "not a serial device"])
    assert "not a serial device" in text, text
    assert running, text
