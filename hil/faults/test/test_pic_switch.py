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


def test_hands_off_sticks_hold_every_aircrafts_elevator_trim():
    """The HiL's pilot trims the transmitter as a pilot does: sticks hands off put the elevator
    (through the HA's receiver mapping, ha_surfaces_from_rc) at the airframe's level trim, not at
    neutral, which dives an aircraft whose cruise needs up elevator (the Aerosonde's -7.6 deg:
    3.7 s of a centred stick and it hit the ground, HiL campaign seed 1 #48)."""
    import glob
    import os
    import yaml
    from hil.faults.base import rc_trimmed
    from stack_tools.paths import ROOT
    folders = sorted(glob.glob(os.path.join(ROOT, "aircraft", "*", "limits.yaml")))
    assert len(folders) >= 2, folders
    for path in folders:
        with open(path) as f:
            limits = yaml.safe_load(f)
        rc = limits["rc"]
        low, high = rc["pulse_min_us"], rc["pulse_max_us"]
        limit_deg = limits["actuators"]["elevator_limit_deg"]
        throttle, elevator, aileron, rudder, pic = rc_trimmed(limits)
        elevator_deg = (elevator - low) * 2.0 * limit_deg / (high - low) - limit_deg
        trim_deg = limits["safety_controller"]["elevator_trim_deg"]
        assert abs(elevator_deg - trim_deg) <= limit_deg / (high - low), (path, elevator_deg, trim_deg)
        assert aileron == rudder == (low + high) // 2, path
        assert pic < rc["pic_threshold_us"] and throttle < (low + high) // 2, path
