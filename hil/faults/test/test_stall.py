"""An HP that flies into a stall with valid commands is taken over by the stall speed."""
from flight import assert_property, fly


def test_an_hp_flying_into_a_stall_is_taken_over():
    s = fly("stall", at_s=12.0, duration_s=-1.0, flight_s=40.0)
    assert_property(s, takeover_due=True)
