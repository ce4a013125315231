"""An HP that climbs through the ceiling with valid commands: the HA has the servos inside its
switch margin below the ceiling (limits.yaml switch_region_fraction), so neither its INS's
height error nor the climb during the takeover carries the aircraft through 400 ft, and it keeps
it inside S_x. (Before the margin, seed 11's INS read ~2 ft low and the truth reached 402 ft.)"""
from stack_testing.fault_flight import assert_property, fly


def test_an_hp_climbing_through_the_ceiling_is_taken_over_before_it_passes():
    s = fly("climb", at_s=10.0, duration_s=-1.0, params=["pitch_deg=15"], flight_s=40.0)
    assert_property(s, takeover_due=None)
    v = s["verdict"]
    assert v["hp_lost_control_s"] is not None, s["_replay"]
    assert any("CEILING" in seg["why"] for seg in s["who_flew"]), s["_replay"]
    assert s["margins"]["min_ceiling_margin_ft"] >= 0.0, s["_replay"]
    assert v["outside_S_x_from_fault_s"] == 0.0, s["_replay"]
