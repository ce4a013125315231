"""A frozen HP (the same command, same sequence number, over and over) is taken over."""
from stack_testing.fault_flight import assert_property, fly


def test_a_frozen_command_is_taken_over_within_one_period():
    s = fly("frozen", at_s=15.0, duration_s=3.0)
    assert_property(s, takeover_due=True)
