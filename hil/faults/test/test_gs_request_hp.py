"""A ground station asks for the HP (MAVLink DO_SET_MODE through microhard_gs) while the HP is
failing (NaN aileron): the HA keeps the failing HP off the servos."""
from stack_testing.fault_flight import assert_property, fly, segments_between


def test_a_ground_station_asking_for_a_failing_hp_does_not_get_it():
    s = fly("gs_request_hp", at_s=15.0, duration_s=6.0, params=["request_after_s=0.5", "request_every_s=2"])
    assert_property(s, takeover_due=True)
    took = s["verdict"]["takeover_s"]
    during = segments_between(s, took, 21.0)
    assert all(seg["controller"] != "HP" for seg in during), (during, s["_replay"])
