"""VN-200 loss on the HA side: the HA cannot judge the state, so it takes the servos within one
period of its state going stale, and flies inside S_x."""
from stack_testing.fault_flight import assert_property, fly


def test_losing_the_has_own_vn200_hands_it_the_servos():
    s = fly("ha_vn200_loss", at_s=15.0, duration_s=3.0)
    assert_property(s, takeover_due=True)


def test_blind_while_the_hp_banks_the_ha_fades_the_aileron_and_the_aircraft_does_not_spiral():
    """Issue 13 item 2 in closed loop: the HA loses its INS for 10 s while the HP is turning. It
    takes the servos (NO_HA_STATE, not a ceiling or region breach), its aileron fades to trim
    within blind_fade_s instead of holding the HP's (a held aileron is a fast spiral, past 60 deg
    in about 2 s): the aircraft stays inside S_x and, once the aileron is at trim, its bank creeps
    by less than 10 deg in the 8 s left (seed 11: -21 deg in, rolling in at 21 deg/s; -37 deg
    when the aileron reaches trim, then a slow creep to -45 deg; see the 30 s story below)."""
    import os
    import yaml
    from stack_testing.fault_flight import ROOT, truth_series
    with open(os.path.join(ROOT, "aircraft", "DG808", "limits.yaml")) as f:
        fade_s = yaml.safe_load(f)["safety_controller"]["blind_fade_s"]
    # At 8.5 s the HP is rolling into its first turn, towards the mission's first waypoint (it gets
    # the servos 2 s later than before issue 22: the HA hands over only on a state of its own that
    # has been whole for the stable window too).
    at_s, duration_s = 8.5, 10.0
    s = fly("ha_vn200_loss", at_s=at_s, duration_s=duration_s, flight_s=30.0)
    assert_property(s, takeover_due=True)
    blind = [seg for seg in s["who_flew"] if seg["controller"] == "HA" and at_s <= seg["from_s"] < at_s + 1.0]
    assert blind and blind[0]["why"] == ["NO_HA_STATE"], (s["who_flew"], s["_replay"])
    truth = {round(m.header.stamp.to_sec(), 2): m for m in truth_series(s)}
    entering = truth[at_s]
    assert abs(entering.roll_deg) > 10.0, "the HP was not banking: %.1f deg (%s)" % (entering.roll_deg, s["_replay"])
    settled = [truth[round(at_s + fade_s + k * 0.01, 2)] for k in range(int((duration_s - fade_s) * 100))]
    assert max(abs(m.aileron_deg) for m in settled) < 1.0, s["_replay"]
    assert abs(settled[-1].roll_deg) - abs(settled[0].roll_deg) < 10.0, (
        "bank grew from %.1f to %.1f deg with the aileron at trim (%s)" % (
            settled[0].roll_deg, settled[-1].roll_deg, s["_replay"]))


def test_a_long_blind_stretch_ends_with_a_hand_back_that_keeps_the_property():
    """The HA blind for 30 s in the HP's first turn (issue 13 item 2, the long story). Seed 11:
    with the aileron at trim the bank creeps from -37 to -55 deg (a slow spiral: the model's glider
    does not level its wings on its own) and the aircraft sinks about 100 ft, inside S_x. When the
    INS returns, the HA hands back 0.24 s later (the HP's commands stayed valid, so the stable
    window ran while the HA was blind). The HP's loops start from the attitude they are handed
    (attitude_cmd_rate_deg_s): before they did, its step back to its own bank command rolled the
    aircraft out of S_x for 0.24 s, and this test was a strict xfail."""
    s = fly("ha_vn200_loss", at_s=6.5, duration_s=30.0, flight_s=45.0)
    assert_property(s, takeover_due=True)
