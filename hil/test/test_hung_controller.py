"""A hung controller (SIGSTOP: its process and its ROS connections stay up, it only stops
answering) is what a respawning launch node cannot fix: the HA takes over, asks for a restart,
hp_supervisor's SIGTERM goes unanswered and its SIGKILL ends it, a new controller starts and the
HA hands control back after the stable window. A whole lockstep flight (hil/run_flight.py)."""
import json
import os
import sys
import tempfile

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
from hil.campaigns.flight import run_completed  # noqa: E402  (a flight that runs out of time, killed whole)


def test_a_hung_controller_is_killed_restarted_and_given_control_back():
    folder = os.path.join(tempfile.mkdtemp(prefix="hil_hang_"), "flight")
    r = run_completed([sys.executable, os.path.join(ROOT, "hil", "run_flight.py"), "--seed", "3",
                       "--duration", "20", "--crash-at", "9", "--fault", "hang", "--no-bag",
                       "--folder", folder, "--quiet"], timeout=900)
    out = r.stdout.decode(errors="replace")
    assert r.returncode == 0, out[-3000:]
    with open(os.path.join(folder, "summary.json")) as f:
        s = json.load(f)
    tk = s["takeover"]
    assert tk["within_one_period_of_deadline_miss"], tk
    assert tk["hand_back_s"] is not None and tk["hand_back_s"] > tk["takeover_s"]
    events = [e["event"] for e in s["events"]]
    assert any("hang injected" in e for e in events), events
    assert any("restarted by hp_supervisor" in e for e in events), events
    with open(os.path.join(folder, "launch.log"), errors="replace") as f:
        log = f.read()
    assert "(hung): SIGKILL" in log
    assert s["unsafe_servo_commands"]["outside_S_u"] == 0
