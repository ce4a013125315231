"""The wind class (hil/faults/wind.py). The tailwind turn: a gust front from straight behind
swings the calm flight's wind to 9 m/s (29.5 ft/s, just inside sensors.max_wind_ftps) over 3 s.
The airspeed falls by the wind faster than the aircraft can gain it back: the HA must take over
for the stall at its switch speed and recover without the wing stalling (the verdict's
stalled_under_ha_s) and without a deep dive. (Named test_wind_fault.py: hil/test/test_wind.py
is the whole stack's wind test.)"""
from stack_testing.fault_flight import assert_property, fly


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


def test_a_healthy_pitot_downwind_at_a_6500_ft_field_keeps_the_hp():
    """Issue 22 F8: at 6,500 ft the pitot reads 0.9 of the true airspeed, so with 28 ft/s from
    behind (8.5 m/s, built up over 10 s) it reads some 60 ft/s while the groundspeed is 94. A rule
    that holds indicated airspeed against groundspeed takes that healthy pitot for a liar: on
    0da675b seed 11 the HA displaced the healthy HP at 20.79 s (NO_HA_STATE) and again at 30.88 s
    for the rest of the flight. The HA must compare like with like (true airspeed through the
    density, a wind it allows)."""
    s = fly("wind", at_s=12.0, duration_s=-1.0, params=["mps=8.5", "ramp_s=10", "from_rel_deg=180"],
            flight_s=40.0, extra=["--field-elevation-ft", "6500"])
    assert_property(s, takeover_due=None)
    assert s["world"]["ias_over_tas"] < 0.92, s["_replay"]
    lied = [seg for seg in s["who_flew"] if seg["from_s"] > 12.0 and "NO_HA_STATE" in seg["why"]]
    assert not lied, (lied, s["_replay"])
