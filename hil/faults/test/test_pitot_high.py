"""Issue 22 F3, the pitot reading high (hil/faults/pitot_high.py): 40 ft/s above the truth, more
than any wind the HA allows, from one period to the next. The HA must reject it within
sensors.airspeed_timeout_s, as a failed read (the class's due), and fly the aircraft itself; the HP, flying on the same pitot, would
slow to a true 20 ft/s. On 0da675b (one-sided lying check) seed 11 kept the HP on the servos: the
wing stalled for 6.9 s and the aircraft fell to 37 ft."""
from stack_testing.fault_flight import assert_property, fly


def test_a_pitot_reading_40_ftps_high_is_rejected_as_a_failed_read_and_the_wing_never_stalls():
    s = fly("pitot_high", at_s=12.0, duration_s=-1.0, flight_s=30.0)
    assert_property(s, takeover_due=True)
    v = s["verdict"]
    assert v["takeover_due_s"] == 12.05, (v, s["_replay"])       # 12 s + airspeed_timeout_s
    assert v["stalled_from_fault_s"] == 0.0, (v, s["_replay"])
    assert v["min_height_agl_ft"] > 150.0, (v, s["_replay"])
