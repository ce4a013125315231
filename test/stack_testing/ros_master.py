"""A rosmaster of a test's own, on a free loopback port, so tests never meet a user's master or
each other's."""
import contextlib
import os
import socket
import subprocess
import time

from stack_testing.processes import end_process
from stack_tools import ports


@contextlib.contextmanager
def private_master(log_dir=None, start_timeout_s=30.0):
    """Yields the environment a node started under it uses (ROS_MASTER_URI and ROS_IP set to the
    master's loopback port; ROS_LOG_DIR too, if log_dir is given). Ends the master on the way out."""
    port = ports.free_port()
    env = dict(os.environ, ROS_MASTER_URI="http://127.0.0.1:%d" % port, ROS_IP="127.0.0.1")
    env.pop("ROS_HOSTNAME", None)
    if log_dir is not None:
        env["ROS_LOG_DIR"] = log_dir
    proc = subprocess.Popen(["rosmaster", "--core", "-p", str(port)], env=env, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL, start_new_session=True)
    try:
        deadline = time.monotonic() + start_timeout_s
        while True:
            try:
                socket.create_connection(("127.0.0.1", port), timeout=0.5).close()
                break
            except OSError:
                assert proc.poll() is None, "rosmaster exited with status %s" % proc.returncode
                assert time.monotonic() < deadline, "rosmaster did not start"
                time.sleep(0.1)
        yield env
    finally:
        end_process(proc, 10)
