"""Lockstep is deterministic: two flights with one seed log the same truth, bit for bit (every
/hil/truth message's serialized bytes, as the simulator logs them in truth.bin, HP crash and
restart included); another seed differs.
Each flight is a full hil/run_flight.py run: its own ROS master, ptys, every HP node."""
import os
import struct
import sys
import tempfile

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
from hil.campaigns.flight import run_completed  # noqa: E402  (a flight that runs out of time, killed whole)
DURATION_S, CRASH_AT_S = "24", "10"


def fly(seed, folder):
    env = dict(os.environ)
    r = run_completed([sys.executable, os.path.join(ROOT, "hil", "run_flight.py"), "--seed", str(seed),
                       "--duration", DURATION_S, "--crash-at", CRASH_AT_S, "--folder", folder, "--quiet"],
                      env=env, timeout=900)
    assert r.returncode == 0, r.stdout.decode(errors="replace")[-3000:]
    import json
    with open(os.path.join(folder, "summary.json")) as f:
        events = [e["event"] for e in json.load(f)["events"]]
    # A bounded wait that ran out is the one way wall-clock timing enters a lockstep flight.
    assert not [e for e in events if "late" in e or "ran out" in e or "did not answer" in e], events
    with open(os.path.join(folder, "launch.log"), errors="replace") as f:
        waits = [line for line in f if "lockstep: stepping at" in line]
    assert not waits, "the controller stepped without a declared input: " + waits[0]
    return truth_log(os.path.join(folder, "truth.bin"))


def truth_log(path):
    """The simulator's own log of every /hil/truth message's serialized bytes (the bag's recorder
    may drop messages on a loaded machine; this log is written in the step itself)."""
    out = []
    with open(path, "rb") as f:
        data = f.read()
    i = 0
    while i < len(data):
        (n,) = struct.unpack_from("<I", data, i)
        out.append(data[i + 4:i + 4 + n])
        i += 4 + n
    return out


@pytest.fixture(scope="module")
def flights():
    if "ROS_DISTRO" not in os.environ and "ROS_PACKAGE_PATH" not in os.environ:
        pytest.fail("the workspace is not sourced (make test does it)")
    d = tempfile.mkdtemp(prefix="hil_determinism_")
    return {name: fly(seed, os.path.join(d, name)) for name, seed in (("a", 5), ("b", 5), ("c", 6))}


def test_the_same_seed_flies_the_same_flight_bit_for_bit(flights):
    a, b = flights["a"], flights["b"]
    assert len(a) == int(float(DURATION_S) * 100) + 1
    first = next((i for i, (x, y) in enumerate(zip(a, b)) if x != y), None)
    assert first is None, "truth differs from step %d on" % first
    assert a == b


def test_another_seed_flies_another_flight(flights):
    a, c = flights["a"], flights["c"]
    assert len(a) == len(c)
    differing = sum(1 for x, y in zip(a, c) if x != y)
    assert differing > len(a) // 2
