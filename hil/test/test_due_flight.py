"""The Due in the loop (run_flight.py --ha due --realtime), against a Due emulated at its three
ports: the sketch's HIL build (HA_DUE_HIL=1: due_hil_board.cpp, the firmware loop, the core) run
on the host on its own clock (arduino_ha/verify/due_hil_on_ptys.cpp), its programming port, native
USB port and RX1 each a pty published where a bench's /dev/ttyACM0, /dev/ttyACM1 and /dev/ttyUSB0
would be. The flight's real `arduino` node opens the programming port; hil/ha_due.py carries the
simulator's records to the native port and the replies back, and copies the VN-200's port 1 to
RX1. Killed while it flies, the HP is taken over in the HA period the deadline is missed, and the
verdict holds; the Due answered each of its periods, dropped no record and read the VN-200's
bytes. Each flight gets a fresh emulated Due (a power cycle: nothing retained from the last)."""
import json
import os
import pathlib
import subprocess
import sys
import time

import pytest

from hil.campaigns.flight import run_completed  # a flight that runs out of time, killed whole
from stack_testing.due_host import build_due_host_programs
from stack_testing.gs_harness import free_port
from stack_testing.processes import end_process

ROOT = pathlib.Path(__file__).resolve().parents[2]
pytestmark = pytest.mark.realtime  # flown alone, after the rest (conftest.py)
CRASH_AT_S = 8.0  # as test_realtime_crash: the HP has the servos from 5 s
DURATION_S = 16
FLIGHTS = 5  # as test_realtime_crash: the HP late before the crash in up to one flight in two here


@pytest.fixture(scope="module")
def emulator(tmp_path_factory):
    return build_due_host_programs(tmp_path_factory.mktemp("board")) / "due_hil_on_ptys"


class EmulatedDue:
    """A fresh emulated Due with its ports under folder; stopped (and its ports gone) on exit."""

    def __init__(self, binary, folder):
        self.ports = {name: str(folder / name) for name in ("ttyACM0", "ttyACM1", "ttyUSB0")}
        self.log = open(folder / "due.log", "w")
        self.proc = subprocess.Popen([str(binary), "--prog", self.ports["ttyACM0"], "--native",
                                      self.ports["ttyACM1"], "--rx1", self.ports["ttyUSB0"]],
                                     stdout=self.log, stderr=subprocess.STDOUT)
        deadline = time.monotonic() + 10.0
        while not all(os.path.exists(p) for p in self.ports.values()):
            assert self.proc.poll() is None and time.monotonic() < deadline, "the emulated Due did not come up"
            time.sleep(0.05)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        end_process(self.proc, grace_s=10)
        self.log.close()


def fly(binary, folder):
    folder.mkdir()
    with EmulatedDue(binary, folder) as due:
        flight = folder / "flight"
        r = run_completed([sys.executable, str(ROOT / "hil" / "run_flight.py"), "--realtime", "--ha", "due",
                           "--due-port", due.ports["ttyACM0"], "--due-native-port", due.ports["ttyACM1"],
                           "--due-ins-port", due.ports["ttyUSB0"], "--duration", str(DURATION_S),
                           "--crash-at", str(CRASH_AT_S), "--no-bag", "--folder", str(flight), "--quiet",
                           # free ground-link ports: real time's default is QGroundControl's 14550/14555
                           "--vehicle-port", str(free_port()), "--gcs-port", str(free_port())],
                          timeout=600)
    assert r.returncode == 0, r.stdout.decode(errors="replace")[-3000:]
    assert not any(os.path.exists(p) for p in due.ports.values()), "the emulated Due left its ports behind"
    with open(flight / "summary.json") as f:
        s = json.load(f)
    with open(flight / "ha_due_replies.txt") as f:
        rows = [[int(v) for v in line.split()] for line in f]
    return s, rows


def hp_flew_at_crash(s):
    # On the HA's own periods, as test_realtime_crash asks: who_flew's simulator steps run after the
    # HA ticks they show and can put a good takeover just before the kill.
    return s["takeover"]["controller_before_crash"] == "HP"


def test_a_crash_with_the_due_in_the_loop_is_taken_over_in_the_period_the_deadline_is_missed(emulator, tmp_path):
    # As in test_realtime_crash: a loaded machine now and then makes the HP late before the crash,
    # and the HA rightly takes over then; such a flight must keep the property, but the next one
    # is flown (at most FLIGHTS) to see the crash's own takeover.
    for k in range(FLIGHTS):
        s, rows = fly(emulator, tmp_path / ("flight%d" % k))
        assert s["mode"] == "realtime" and s["verdict"]["ok"], s["verdict"]
        if hp_flew_at_crash(s):
            break
    assert hp_flew_at_crash(s), (s["takeover"], s["who_flew"])
    assert s["status"] == "ok", s["fault"]
    tk, v = s["takeover"], s["verdict"]
    assert CRASH_AT_S <= tk["first_missed_period_s"] < tk["deadline_miss_s"], tk
    assert tk["latency_after_deadline_miss_s"] == 0.0 and tk["within_one_period_of_deadline_miss"], tk
    assert tk["reasons_at_switch"] & 2, tk  # DEADLINE_MISS
    assert v["unsafe_commands"] == 0 and v["envelope_violations_under_ha_s"] == 0.0, v
    # The Due answered its own periods (its clock: a reply each 10 ms, in order, the flight's
    # length of them; a host stalled past a period restarts the schedule, so a few may be
    # missing), dropped no record, could send every reply once the simulator had its port open
    # (the count is since power-up, when nobody read the port), and no VN-200 byte was lost on
    # the way to RX1. Each line (record_bridge.RecordBridge): the period on the Due's clock and on
    # the host's, records dropped, loop pass us, reply bytes not sent, bytes lost on receive (none
    # with USB's flow control), VN-200 bytes not passed on.
    assert len(rows) >= DURATION_S * 100 * 0.9, len(rows)
    for col in (0, 1):  # each clock's microseconds wrap at 2^32 (71 min)
        assert all(0 < (b[col] - a[col]) % 2 ** 32 < 2 ** 31 for a, b in zip(rows, rows[1:])), \
            "a reply out of order or twice"
    assert all(row[2] == 0 and row[4] == rows[0][4] and row[5] == 0 and row[6] == 0 for row in rows)
