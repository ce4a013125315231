"""The HP crash in real time (issue 24): the HA SIL runs its periods on its own clock, the
controller on its own timer, the simulator on the wall clock, each at whatever phase to the
others. Killed while it flies, the HP is taken over in the very HA period the deadline is
missed (the second HA period in a row without a new command), and the verdict holds: it judges
the takeover on the HA's own ticks (hil/README.md, "Deadline semantics"). Whole real-time
flights (hil/run_flight.py --realtime), 16 s of wall time each: with the SIL, and with the HA as
Cortex-M3 machine code in QEMU keeping its own clock (--ha qemu: the PIL_REALTIME board, its
ticks put on the host's clock by hil/record_bridge.py), which must also answer its periods in
order with no record dropped and no byte lost to a full receive ring."""
import json
import os
import sys
import tempfile

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
from hil.campaigns.flight import run_completed  # noqa: E402  (a flight that runs out of time, killed whole)
from stack_testing.gs_harness import free_port  # noqa: E402
from stack_testing.ha_in_loop import build_pil_image, loop_speed  # noqa: E402

CRASH_AT_S = 8.0  # the HP has the servos from 5 s (the airborne start at 2 s, 1 s, the stable window)
# A flight whose HP is late before the crash is flown again. On the slow CI machine (QEMU's PIL
# loop at 1.1x) 3 flights of 6 were, in one batch, and 1 of 8 in the next: at one in two, 3 tries
# fail one run in 8, 5 tries one in 32. A flight is some 20 s; a good first one ends the test.
FLIGHTS = 5
# In a real-time flight QEMU must emulate each of the Due's periods within the period, beside the
# simulator, the HP's nodes and the bridge on the same 2 cores. It can when it runs the PIL loop
# (make bench-pil's, lockstep) at 2x real time or more, so that it needs at most half a core: on
# the machine whose loop ran 4.9x the flight passed in every CI run; on one whose loop ran 0.99x
# (QEMU a whole core) the board fell behind, lost bytes of the HP link and its reports, and
# three flights of three broke the verdict. There the flight judges the host, not the HA.
MIN_PIL_LOOP_X = 2.0
pytestmark = pytest.mark.realtime  # flown alone, after the rest (conftest.py)


def fly_realtime_crash(ha="sil"):
    folder = os.path.join(tempfile.mkdtemp(prefix="hil_rt_crash_"), "flight")
    # Real time puts the ground link on QGroundControl's fixed ports (14550/14555) unless told
    # otherwise: free ones, so two real-time flights of a test run never share them.
    r = run_completed([sys.executable, os.path.join(ROOT, "hil", "run_flight.py"), "--realtime", "--ha", ha,
                       "--duration", "16", "--crash-at", str(CRASH_AT_S), "--no-bag", "--folder", folder,
                       "--vehicle-port", str(free_port()), "--gcs-port", str(free_port()),
                       "--quiet"], timeout=600)
    out = r.stdout.decode(errors="replace")
    assert r.returncode == 0, out[-3000:]
    with open(os.path.join(folder, "summary.json")) as f:
        s = json.load(f)
    assert s["mode"] == "realtime", s["mode"]
    s["folder"] = folder
    return s


def hp_flew_at_crash(s):
    # On the HA's own periods, as the takeover is judged; not who_flew's simulator periods: a step
    # of the simulator runs after the HA ticks it shows. In CI (2026-12-07) three flights of three
    # had the HP until the kill at 8.0 s and the HA's takeover at 8.017 s, yet the simulator's
    # period of 8.00 s already showed the HA, and the test failed; here 3 flights of 8 did.
    return s["takeover"]["controller_before_crash"] == "HP"


def fly_until_the_hp_flies_at_the_crash(ha):
    # On a loaded machine the HP is now and then late by more than the one tolerated period
    # before the crash, and the HA rightly takes over and restarts it: such a flight must keep
    # the property too, but does not test the crash's takeover; the next one is flown (at most
    # FLIGHTS), and one of them must have the HP on the servos when it is killed.
    flown = []
    for _ in range(FLIGHTS):
        s = fly_realtime_crash(ha)
        flown.append(s)
        # In full (a dict is cut short in pytest's message), with the folder the flight's logs are in.
        assert s["verdict"]["ok"], json.dumps({k: s.get(k) for k in ("folder", "verdict", "takeover", "who_flew")})
        if hp_flew_at_crash(s):
            break
    assert hp_flew_at_crash(s), [x["who_flew"] for x in flown]
    return s


def assert_taken_over_in_the_period_the_deadline_is_missed(s):
    assert s["status"] == "ok", s["fault"]
    tk, v = s["takeover"], s["verdict"]
    assert CRASH_AT_S <= tk["first_missed_period_s"] < tk["deadline_miss_s"], tk
    assert tk["latency_after_deadline_miss_s"] == 0.0 and tk["within_one_period_of_deadline_miss"], tk
    assert tk["reasons_at_switch"] & 2, tk  # DEADLINE_MISS
    assert v["takeover_within_one_period"] and v["takeover_latency_s"] == 0.0, v
    assert v["unsafe_commands"] == 0 and v["envelope_violations_under_ha_s"] == 0.0, v


def test_a_crash_in_real_time_is_taken_over_in_the_period_the_deadline_is_missed():
    assert_taken_over_in_the_period_the_deadline_is_missed(fly_until_the_hp_flies_at_the_crash("sil"))


def qemu_keeps_the_dues_real_time():
    """Measured here and now: (whether QEMU runs the PIL loop at MIN_PIL_LOOP_X, what it ran)."""
    steps_per_s, cpu = loop_speed(build_pil_image(tempfile.mkdtemp(prefix="rt_pil_")), steps=300)
    x = steps_per_s / 100.0
    return x >= MIN_PIL_LOOP_X, "QEMU ran the PIL loop at %.2fx real time (%.0f %% of a core); a real-time " \
        "flight with the HA in QEMU needs %.1fx on this machine's cores" % (x, cpu, MIN_PIL_LOOP_X)


def test_a_crash_in_real_time_with_the_ha_in_qemu_is_taken_over_in_the_period_the_deadline_is_missed():
    fast_enough, measured = qemu_keeps_the_dues_real_time()
    if not fast_enough:
        pytest.skip("this machine cannot emulate the Due in real time: " + measured)
    s = fly_until_the_hp_flies_at_the_crash("qemu")
    assert_taken_over_in_the_period_the_deadline_is_missed(s)
    # The board answered its own periods, in order (on its clock and on the host's), about one a
    # period (a board behind by a period restarts its schedule), with no record dropped and no
    # byte lost to a full receive ring. Bytes its UARTs could not send in 2 ms are dropped as a
    # full USB buffer drops them; the link is built for that.
    with open(os.path.join(s["folder"], "ha_qemu_replies.txt")) as f:
        rows = [[int(v) for v in line.split()] for line in f]
    assert len(rows) >= 16 * 100 * 0.9, len(rows)
    for col in (0, 1):  # each clock's microseconds wrap at 2^32 (71 min)
        assert all(0 < (b[col] - a[col]) % 2 ** 32 < 2 ** 31 for a, b in zip(rows, rows[1:])), \
            "a reply out of order or twice"
    assert all(row[2] == 0 and row[5] == 0 for row in rows)
