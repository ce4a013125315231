"""Issue 22 F3 in closed loop: a pitot iced at 85 ft/s (hil/faults/pitot_stuck.py) in still air.
The HP flies on the same pitot, so it slows the aircraft to make the reading what it wants; once
the reading is more than any wind the HA allows (sensors.max_wind_ftps) above the INS's speed it
can only be a lying sensor, and the HA must have taken over by then (the class's due; an HA that
learns the wind may see it sooner, and then no due comes). On 0da675b the lying check was
one-sided: seed 11 had the due at 14.08 s, the HP kept the servos, the wing stalled and the
aircraft hit the ground. With the two-sided test alone the HA took the servos for STALL but handed
them back to the HP, which flew on the stuck pitot into three more STALL takeovers and 1.0 s of
stalled wing under the HA; a reading repeated to the bit for sensors.pitot_stuck_s is now a stuck
sensor, and the HA keeps the servos."""
from stack_testing.fault_flight import assert_property, fly


def test_a_pitot_iced_at_85_ftps_in_still_air_is_rejected_before_the_hp_slows_into_the_stall():
    s = fly("pitot_stuck", at_s=12.0, duration_s=-1.0, params=["value_ftps=85"], flight_s=35.0)
    assert_property(s, takeover_due=None)
    v = s["verdict"]
    assert v["hp_lost_control_s"] is not None and v["hp_lost_control_s"] > 12.0, (v, s["_replay"])
    assert v["stalled_from_fault_s"] == 0.0, (v, s["_replay"])
    assert v["min_height_agl_ft"] > 100.0, (v, s["_replay"])
