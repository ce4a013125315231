"""What the launch tests share: a free loopback port, a wait on a condition, and stopping every
process a test started (SIGINT first, so roslaunch takes its nodes down, then SIGKILL)."""
import os
import signal
import socket
import subprocess
import time

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
