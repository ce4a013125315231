"""A NaN in one surface with a valid CRC never reaches a servo: the HA drives its own command from
the period the NaN arrives."""
from stack_testing.fault_flight import assert_property, fly


def test_a_nan_aileron_never_reaches_the_servos():
    # With its bag: drone_ros/report/test/test_report_of_a_hil_fault_flight.py reads this flight too.
    s = fly("nan", at_s=15.0, duration_s=3.0, params=["surface=aileron"], bag=True)
    assert_property(s, takeover_due=True)
