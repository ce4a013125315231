"""Issue 13's stories in closed loop, an HP flying low and slow with valid commands
(hil/faults/low_slow.py):
- a low pass at 20-25 ft, below airborne_agl_ft: nothing is wrong, so the HP keeps the servos,
  the motor keeps running and the aircraft climbs away (height alone once cut the motor);
- slowing to a stall at 60 ft: the HA takes over at its stall switch speed and lowers the nose
  (slow beats low) without touching the ground;
- airspeed held at stall: every takeover is for STALL, every hand-back comes after the stable
  window at or above the hand-back speed (no cycling on airspeed noise), and an HP that keeps
  doing it is latched out at the restart cap."""
import os
import re

import yaml
from stack_testing.fault_flight import ROOT, assert_property, fly, segments_between

with open(os.path.join(ROOT, "aircraft", "DG808", "limits.yaml")) as _f:
    _STATE = yaml.safe_load(_f)["state"]
AIRBORNE_FT = _STATE["airborne_agl_ft"]
HANDBACK_FTPS = _STATE["stall_speed_ftps"] * _STATE["handback_stall_multiple"]


def low_point(s):
    m = re.search(r"lowest ([\d.-]+) ft at ([\d.]+) s, throttle applied there ([\d.]+), calibrated airspeed "
                  r"([\d.]+) ft/s; ([\d.-]+) ft at the end", s["fault"]["evidence"])
    assert m, s["fault"]["evidence"]
    return [float(v) for v in m.groups()]


def test_a_low_pass_below_the_airborne_height_keeps_the_hp_and_the_motor():
    s = fly("low_slow", at_s=12.0, duration_s=-1.0, params=["height_ft=20", "pass_s=8"], flight_s=75.0)
    assert_property(s, takeover_due=False)
    lowest_ft, _, throttle, _, end_ft = low_point(s)
    assert 5.0 < lowest_ft < AIRBORNE_FT, s["_replay"]
    assert throttle > 0.05, s["_replay"]  # the motor ran at the lowest point
    assert [seg["controller"] for seg in segments_between(s, 12.0, 75.0)] == ["HP"], s["_replay"]
    assert end_ft > 100.0, s["_replay"]   # and the aircraft climbed away


def test_slowing_to_a_stall_at_60_ft_is_taken_over_and_recovered_above_the_ground():
    s = fly("low_slow", at_s=12.0, duration_s=-1.0, params=["height_ft=60", "airspeed_ftps=38"], flight_s=70.0)
    assert_property(s, takeover_due=None)
    takeovers = [seg for seg in s["who_flew"] if seg["controller"] == "HA" and seg["from_s"] > 12.0]
    assert takeovers and all(seg["why"] == ["STALL"] for seg in takeovers), s["_replay"]
    v = s["verdict"]
    assert v["min_height_agl_ft"] > 5.0 and not v["aircraft_crashed"], s["_replay"]
    assert v["min_airspeed_margin_ftps"] > 0.0, s["_replay"]  # the wing never stalled


def test_airspeed_held_at_stall_hands_back_only_with_margin_and_latches_a_persistent_hp():
    s = fly("low_slow", at_s=12.0, duration_s=-1.0, params=["height_ft=200", "airspeed_ftps=42"], flight_s=90.0)
    assert_property(s, takeover_due=None)
    takeovers = [seg for seg in s["who_flew"] if seg["controller"] == "HA" and seg["from_s"] > 12.0]
    assert len(takeovers) >= 2 and all(seg["why"] == ["STALL"] for seg in takeovers), s["_replay"]
    for hb in s["hand_backs"]:
        assert hb["after_stable_window"] and hb["calibrated_airspeed_ftps"] >= HANDBACK_FTPS, (hb, s["_replay"])
    assert s["verdict"]["latched"], s["_replay"]
