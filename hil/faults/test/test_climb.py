"""An HP that climbs through the ceiling with valid commands: the HA has the servos by the time
the aircraft passes 400 ft and keeps it inside S_x."""
from flight import assert_property, fly


def test_an_hp_climbing_through_the_ceiling_is_taken_over():
    s = fly("climb", at_s=12.0, duration_s=-1.0, flight_s=45.0)
    assert_property(s, takeover_due=True)
