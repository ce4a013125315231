"""The pilot's PIC switch mid-fault: the HP crashes, the HA takes over, the pilot switches to
manual one second later and has the servos that period, and hands back to the computer."""
from stack_testing.fault_flight import HA_PERIOD_S, assert_property, fly, segments_between


def test_the_pilots_switch_wins_during_an_hp_crash_and_gives_back_to_the_computer():
    s = fly("pic_switch", at_s=15.0, params=["switch_after_s=1", "switch_s=3"], flight_s=30.0)
    assert_property(s, takeover_due=True)
    manual = [seg for seg in s["who_flew"] if seg["controller"] == "MANUAL"]
    assert manual, (s["who_flew"], s["_replay"])
    assert 16.0 - 1e-6 <= manual[0]["from_s"] <= 16.0 + HA_PERIOD_S + 1e-6, (manual, s["_replay"])
    after = segments_between(s, 19.0 + HA_PERIOD_S, 30.0)
    assert after and all(seg["controller"] != "MANUAL" for seg in after), (after, s["_replay"])
