"""Tests stop what they started with Ctrl-C: SIGINT to its process group. That has to work however
pytest itself was started. A shell running `make test &` without job control (a script, CI,
nohup) starts it with SIGINT ignored, and its children would inherit that and sit out every stop
until killed; the root conftest.py hands them the default action again."""
import os
import signal
import subprocess
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))


def test_a_process_a_test_started_stops_on_ctrl_c():
    child = subprocess.Popen(["sleep", "60"], start_new_session=True)
    try:
        os.killpg(child.pid, signal.SIGINT)
        assert child.wait(timeout=10) == -signal.SIGINT
    finally:
        if child.poll() is None:
            child.kill()
            child.wait()


def test_it_stops_on_ctrl_c_when_pytest_was_started_with_sigint_ignored():
    # As `make test &` in a script starts it: SIGINT ignored, then exec.
    start_ignoring = ("import os, signal, sys; signal.signal(signal.SIGINT, signal.SIG_IGN); "
                      "os.execv(sys.executable, [sys.executable] + sys.argv[1:])")
    inner = os.path.relpath(__file__, ROOT) + "::test_a_process_a_test_started_stops_on_ctrl_c"
    r = subprocess.run([sys.executable, "-c", start_ignoring, "-m", "pytest", "-q", "-p", "no:cacheprovider",
                        inner], cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stdout[-3000:] + r.stderr[-1000:]
