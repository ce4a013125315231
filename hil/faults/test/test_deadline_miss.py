"""Deadline misses: one late period is tolerated (limits.yaml late_periods_tolerated), a hiccup of
two or more is not; repeated hiccups of 3 periods are taken over within one period."""
from stack_testing.fault_flight import assert_property, fly


def test_one_command_half_a_period_late_is_tolerated_and_the_hp_keeps_flying():
    s = fly("deadline_miss", at_s=15.0, duration_s=1.0, params=["delay_periods=0.5"], flight_s=25.0)
    assert_property(s, takeover_due=False)
    assert s["verdict"]["hp_lost_control_s"] is None, s["_replay"]


def test_repeated_three_period_hiccups_hand_the_servos_to_the_ha_within_one_period():
    s = fly("deadline_miss", at_s=15.0, duration_s=5.0,
            params=["delay_periods=3", "repeat_every_periods=10"])
    assert_property(s, takeover_due=True)
