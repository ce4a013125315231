"""What the per-class fault tests share: one short lockstep flight through hil/run_flight.py (its
own ROS master, ptys and folder) with one fault, and the Simplex property asserted on its verdict,
which comes from the simulator's truth."""
import json
import os
import sys

from stack_tools.paths import ROOT  # noqa: E402
from hil.campaigns.flight import run_once_per_test_run  # noqa: E402  (killed whole if out of time; shared)
from hil.aircraft_period import decision_rate_hz  # noqa: E402
HA_PERIOD_S = 1.0 / decision_rate_hz(os.path.join(ROOT, "aircraft", "DG808"))


def fly(fault, at_s=15.0, duration_s=-1.0, params=(), flight_s=35.0, seed=11, extra=(), bag=False):
    """Flies and returns the summary (with its replay command and folder); extra: more
    run_flight.py arguments (the world: --field-elevation-ft, --temperature-c, ...); bag: record
    flight.bag and write its report. Tests asking for the same flight share it (one flight per
    scenario per test run, hil/campaigns/flight.py run_once_per_test_run)."""
    if "ROS_DISTRO" not in os.environ and "ROS_PACKAGE_PATH" not in os.environ:
        raise AssertionError("the workspace is not sourced (make test does it)")
    argv = [os.path.join(ROOT, "hil", "run_flight.py"), "--seed", str(seed), "--fault", fault,
            "--fault-at", "%g" % at_s, "--fault-duration", "%g" % duration_s, "--duration", "%g" % flight_s]
    for p in params:
        argv += ["--fault-param", p]
    argv += list(extra) + ([] if bag else ["--no-bag"]) + ["--quiet"]
    r, folder = run_once_per_test_run([sys.executable] + argv, timeout=1200)
    replay = "hil/run_flight.py " + " ".join(argv[1:])
    out = r.stdout.decode(errors="replace")
    assert r.returncode == 0, "flight failed (%s):\n%s" % (replay, out[-3000:])
    with open(os.path.join(folder, "summary.json")) as f:
        s = json.load(f)
    s["_replay"] = replay
    s["_folder"] = folder
    return s


def truth_series(s):
    """Every step's /hil/truth of the flight (the simulator's own log, truth.bin), in order."""
    import struct
    from drone_ros.msg import HilTruth
    with open(os.path.join(s["_folder"], "truth.bin"), "rb") as f:
        data = f.read()
    out, i = [], 0
    while i < len(data):
        (n,) = struct.unpack_from("<I", data, i)
        out.append(HilTruth().deserialize(data[i + 4:i + 4 + n]))
        i += 4 + n
    return out


def assert_property(s, takeover_due):
    """The fault took effect; no servo command outside S_u; the aircraft never outside S_x while
    the HA flew; and where a takeover was due, the HA had the servos within one HA period of the
    deadline. takeover_due: True (the class makes one due), False (it must not), None (either)."""
    f, v = s["fault"], s["verdict"]
    why = "%s\nfault: %s\nverdict: %s\nreplay: %s" % (s["status"], json.dumps(f), json.dumps(v), s["_replay"])
    assert s["status"] == "ok" and f["took_effect"], why
    assert v["unsafe_commands"] == 0, why
    assert v["envelope_violations_under_ha_s"] == 0.0, why
    assert not v["aircraft_crashed"], why
    if takeover_due is True:
        assert v["takeover_due_s"] is not None, why
    if takeover_due is False:
        assert v["takeover_due_s"] is None, why
    if v["takeover_due_s"] is not None:
        assert v["takeover_latency_s"] is not None and v["takeover_latency_s"] <= HA_PERIOD_S + 1e-9, why
    assert v["ok"], why
    return why


def segments_between(s, t0, t1):
    """The controllers that flew at some time in [t0, t1)."""
    return [seg for seg in s["who_flew"] if seg["from_s"] < t1 and seg["to_s"] > t0]
