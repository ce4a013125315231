"""A stale replay of an old valid command (its own good CRC) is taken over."""
from stack_testing.fault_flight import assert_property, fly


def test_a_replayed_second_old_command_is_taken_over_within_one_period():
    s = fly("stale_replay", at_s=15.0, duration_s=3.0, params=["age_s=1.0"])
    assert_property(s, takeover_due=True)
