"""The wind class (hil/faults/wind.py), the tailwind turn: a gust front from straight behind
swings the calm flight's wind to 9 m/s (29.5 ft/s, just inside sensors.max_wind_ftps) over 3 s.
The airspeed falls by the wind faster than the aircraft can gain it back: the HA must take over
for the stall at its switch speed and recover without the wing stalling (the verdict's
stalled_under_ha_s) and without a deep dive. (Named test_wind_fault.py: hil/test/test_wind.py
is the whole stack's wind test.)"""
from flight import assert_property, fly


def test_a_tailwind_gust_front_is_taken_over_for_the_stall_and_recovered_with_the_wing_flying():
    s = fly("wind", at_s=12.0, duration_s=-1.0, params=["mps=9", "ramp_s=3", "from_rel_deg=180"], flight_s=30.0)
    assert_property(s, takeover_due=None)
    v = s["verdict"]
    assert s["world"]["wind_at_end"]["mps"] == 9.0, s["_replay"]
    assert any(seg["controller"] == "HA" and "STALL" in seg["why"] and seg["from_s"] > 12.0
               for seg in s["who_flew"]), s["_replay"]
    assert v["stalled_from_fault_s"] == 0.0, (v, s["_replay"])
    assert v["recovery_height_loss_ft"] is not None and v["recovery_height_loss_ft"] < 40.0, (v, s["_replay"])
    assert v["min_height_agl_ft"] > 150.0, (v, s["_replay"])
