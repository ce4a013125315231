"""A dead pitot on the HA: once the held reading runs out the HA lacks state and takes over."""
from flight import assert_property, fly


def test_a_dead_pitot_hands_the_servos_to_the_ha():
    s = fly("pitot_failure", at_s=15.0, duration_s=3.0, params=["mode=dead"])
    assert_property(s, takeover_due=True)
