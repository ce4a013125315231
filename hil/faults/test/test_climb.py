"""An HP that climbs through the ceiling with valid commands: the HA has the servos before the
aircraft passes 400 ft (its INS may see the ceiling a few feet early: then no takeover falls due
on the truth, and the aircraft never passed it) and keeps it inside S_x."""
import pytest
from flight import assert_property, fly


@pytest.mark.xfail(strict=True, reason="the HA's ceiling check has no margin for its INS's height error: "
                                       "seed 11 reads ~2 ft low and the truth reaches 402 ft under the HP (finding)")
def test_an_hp_climbing_through_the_ceiling_is_taken_over_before_it_passes():
    s = fly("climb", at_s=10.0, duration_s=-1.0, params=["pitch_deg=15"], flight_s=40.0)
    assert_property(s, takeover_due=None)
    v = s["verdict"]
    assert v["hp_lost_control_s"] is not None, s["_replay"]
    assert s["margins"]["min_ceiling_margin_ft"] >= 0.0, s["_replay"]
