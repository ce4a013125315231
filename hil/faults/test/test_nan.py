"""A NaN in one surface with a valid CRC never reaches a servo: the HA drives its own command from
the period the NaN arrives."""
from flight import assert_property, fly


def test_a_nan_aileron_never_reaches_the_servos():
    s = fly("nan", at_s=15.0, duration_s=3.0, params=["surface=aileron"])
    assert_property(s, takeover_due=True)
