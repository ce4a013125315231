"""RC loss with the receiver's PIC channel reading "pilot": the lost receiver never gets the
servos (no MANUAL), the computer stays in command."""
from stack_testing.fault_flight import assert_property, fly, segments_between


def test_a_lost_receiver_reading_pilot_never_takes_the_servos():
    s = fly("rc_loss", at_s=15.0, duration_s=3.0, params=["pic_us=2000"], flight_s=25.0)
    assert_property(s, takeover_due=None)
    during = segments_between(s, 15.0, 18.0)
    assert all(seg["controller"] != "MANUAL" for seg in during), (during, s["_replay"])
