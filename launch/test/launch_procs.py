"""What the launch tests share: a free loopback port, a wait on a condition, a roscore of the
test's own to launch on, and stopping every process a test started (SIGINT first, so roslaunch
takes its nodes down, then SIGKILL)."""
import contextlib
import os
import signal
import socket
import subprocess
import tempfile
import time

import pytest
import rosgraph
import yaml
from stack_tools import ports


def free_port(kind=socket.SOCK_STREAM):
    return ports.free_port(kind)


def stop(procs):
    for p in reversed(procs):
        if p.poll() is None:
            os.killpg(p.pid, signal.SIGINT)
    for p in reversed(procs):
        try:
            p.wait(timeout=20)
        except subprocess.TimeoutExpired:
            os.killpg(p.pid, signal.SIGKILL)
            p.wait()


def wait_for(cond, timeout_s=120.0):
    """cond()'s first true value within timeout_s, else its last value."""
    deadline = time.time() + timeout_s
    while time.time() < deadline:
        value = cond()
        if value:
            return value
        time.sleep(0.1)
    return cond()


def echo(env, topic, count, timeout_s=120):
    """`count` messages of topic, as dicts (rostopic echo's YAML)."""
    out = subprocess.run(["rostopic", "echo", "-n", str(count), topic], env=env, capture_output=True,
                         text=True, timeout=timeout_s)
    assert out.returncode == 0, "%s: %s" % (topic, out.stderr[-500:])
    return [d for d in yaml.safe_load_all(out.stdout) if d]


def master_up(master):
    try:
        master.getPid()
        return True
    except OSError:
        return False


@contextlib.contextmanager
def private_master(prefix, caller_id):
    """A roscore of its own on a free port, so tests running beside this one (make test's two
    workers) launch nothing onto it: yields (master, env, run_dir, start). start(cmd) runs cmd
    against it in its own process group, its output in run_dir/N.log; on leaving, everything
    started is stopped."""
    if "ROS_PACKAGE_PATH" not in os.environ:
        pytest.fail("the workspace is not sourced (make test does it)")
    port = free_port()
    run_dir = tempfile.mkdtemp(prefix=prefix)
    env = dict(os.environ, ROS_MASTER_URI="http://127.0.0.1:%d" % port, ROS_IP="127.0.0.1",
               ROS_LOG_DIR=os.path.join(run_dir, "ros"), PYTHONUNBUFFERED="1")
    env.pop("ROS_HOSTNAME", None)
    procs = []

    def start(cmd):
        log = open(os.path.join(run_dir, "%d.log" % len(procs)), "wb")
        procs.append(subprocess.Popen(cmd, env=env, stdout=log, stderr=subprocess.STDOUT,
                                      start_new_session=True))

    try:
        start(["roscore", "-p", str(port)])
        master = rosgraph.Master(caller_id, master_uri=env["ROS_MASTER_URI"])
        if not wait_for(lambda: master_up(master), 60.0):
            raise RuntimeError("roscore did not come up")
        yield master, env, run_dir, start
    finally:
        stop(procs)
