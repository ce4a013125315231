"""Issue 22, F6: power-up with no GNSS fix and a dead pitot. The HA used to spin the motor to its
trim on the ground ("blind counts as airborne"). Power-up is on the ground until a sign of flight:
the motor idles parked the whole time, home latches once the fix and the pitot are there, and the
flight goes on as usual after the airborne start."""
import os

import yaml

from stack_testing.fault_flight import ROOT, assert_property, fly, truth_series

with open(os.path.join(ROOT, "aircraft", "DG808", "limits.yaml")) as _f:
    THROTTLE_MIN = float(yaml.safe_load(_f)["actuators"]["throttle_min"])


def test_a_cold_start_without_fix_or_pitot_keeps_the_motor_idle_on_the_ground():
    s = fly("cold_start", at_s=6.0, duration_s=-1.0, flight_s=30.0)
    why = assert_property(s, takeover_due=None)
    d = s["fault"]["detail"]
    assert d["blind_steps"] >= 500 and d["ground_steps"] >= 800, why
    assert d["max_ground_throttle"] <= THROTTLE_MIN + 1e-6, why
    assert d["home_s"] is not None and 6.0 <= d["home_s"] < 7.0, why  # once the fix and the pitot are there
    parked = [m for m in truth_series(s) if m.on_ground]
    assert len(parked) >= 800 and max(m.throttle for m in parked) <= THROTTLE_MIN + 1e-6, why
    # After the airborne start the HP flies the mission as usual.
    assert s["verdict"]["recovery_s"] is not None, why
    assert any(seg["controller"] == "HP" for seg in s["who_flew"]), why
