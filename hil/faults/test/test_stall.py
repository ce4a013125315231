"""An HP that flies into a stall with valid commands is taken over above stall speed.

The HA's pitot sees a stall several periods late (AMS5812 offset and noise), so it switches at
stall_speed_ftps x stall_switch_multiple (limits.yaml) and lowers the nose while the wing still
flies; the truth's calibrated airspeed never reaches the stall speed. The HP, restarted and given
control back, pulls up again until the restart cap latches it out. (Before the switch speed,
seed 11 departed: 1.34 s outside S_x under the HA, roll rate -563 deg/s in a snap roll.)"""
from stack_testing.fault_flight import assert_property, fly


def test_an_hp_flying_into_a_stall_is_taken_over_before_the_stall():
    s = fly("stall", at_s=12.0, duration_s=-1.0, flight_s=40.0)
    assert_property(s, takeover_due=None)
    v = s["verdict"]
    assert v["hp_lost_control_s"] is not None, s["_replay"]
    assert any(seg["controller"] == "HA" and "STALL" in seg["why"] for seg in s["who_flew"]), s["_replay"]
    assert v["min_airspeed_margin_ftps"] > 0.0, s["_replay"]
    assert v["outside_S_x_from_fault_s"] == 0.0, s["_replay"]
