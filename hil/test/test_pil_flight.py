"""The case study with the HA as Cortex-M3 machine code (run_flight.py --ha qemu), shortened to
60 s with the controller SIGKILLed at 30 s: a whole lockstep flight with the real HP nodes, the
HA's firmware image in QEMU's mps2-an385 on the HP link, the VN-200 and the control records.
The HA takes over within one period of the missed deadline, hands back to the HP after the stable
window, commands nothing outside S_u, and the verdict holds; the image in the flight's folder
answered every step, with no record or UART byte dropped."""
import json
import os
import sys
import tempfile

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
from hil.campaigns.flight import run_completed  # noqa: E402  (a flight that runs out of time, killed whole)

DURATION_S, CRASH_AT_S = 60, 30


def test_the_case_study_with_the_ha_in_qemu_takes_over_in_one_period_and_hands_back():
    folder = os.path.join(tempfile.mkdtemp(prefix="hil_pil_flight_"), "flight")
    r = run_completed([sys.executable, os.path.join(ROOT, "hil", "run_flight.py"), "--ha", "qemu",
                       "--seed", "1", "--duration", str(DURATION_S), "--crash-at", str(CRASH_AT_S),
                       "--no-bag", "--folder", folder, "--quiet"], timeout=900)
    out = r.stdout.decode(errors="replace")
    assert r.returncode == 0, out[-3000:]
    with open(os.path.join(folder, "summary.json")) as f:
        s = json.load(f)
    tk = s["takeover"]
    assert tk["crash_injected_s"] == CRASH_AT_S
    assert tk["within_one_period_of_deadline_miss"], tk
    assert tk["takeover_s"] - tk["deadline_miss_s"] <= 0.01 + 1e-6
    assert tk["hand_back_s"] is not None and tk["hand_back_s"] > tk["takeover_s"]
    assert [w["controller"] for w in s["who_flew"]][-1] == "HP"
    assert s["unsafe_servo_commands"]["outside_S_u"] == 0
    assert s["verdict"]["ok"] and s["status"] == "ok", s["verdict"]
    # QEMU flew it: the image it built is in the folder, and its board answered every step (one
    # reply line a step record: t_us, records dropped, ticks, bytes the UARTs could not send,
    # bytes its pty could not take, bytes to a full receive ring).
    assert os.path.getsize(os.path.join(folder, "pil", "ha_pil.elf")) > 0
    with open(os.path.join(folder, "ha_qemu_replies.txt")) as f:
        rows = [[int(v) for v in line.split()] for line in f]
    steps = {row[0] for row in rows}
    assert {k * 10000 for k in range(DURATION_S * 100 + 1)} <= steps
    assert all(row[1] == 0 and row[3] == 0 and row[5] == 0 for row in rows)
