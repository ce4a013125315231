"""An elevator beyond its limit (outside S_u) never reaches the servo."""
from stack_testing.fault_flight import assert_property, fly


def test_an_elevator_past_its_limit_never_reaches_the_servo():
    s = fly("out_of_range", at_s=15.0, duration_s=3.0, params=["surface=elevator"])
    assert_property(s, takeover_due=True)
