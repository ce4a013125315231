"""Ending a process a test started: asked first, forced if it does not go."""
import signal
import subprocess


def end_process(proc, grace_s):
    """SIGTERM to proc, SIGKILL if it outlives grace_s; reaped either way."""
    proc.send_signal(signal.SIGTERM)
    try:
        proc.wait(timeout=grace_s)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.wait()
