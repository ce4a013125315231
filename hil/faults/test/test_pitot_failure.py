"""A dead, zeroed or low pitot on the HA: once the held reading runs out the HA lacks state and
takes over, and flies without the stall it could not see."""
from stack_testing.fault_flight import assert_property, fly


def test_a_dead_pitot_hands_the_servos_to_the_ha():
    s = fly("pitot_failure", at_s=15.0, duration_s=3.0, params=["mode=dead"])
    assert_property(s, takeover_due=True)


def test_a_pitot_reading_zero_in_cruise_is_not_flown_as_a_stall_into_the_ground():
    """The campaign's flight 0 (seed 7): a zeroed pitot at 19 s. Believed, the HA's slow-beats-low
    law pushed the nose down for 12 s and hit the ground sinking at 4.8 m/s. The HA now holds a
    reading that far below its INS's groundspeed for a lying sensor (sensors.max_wind_ftps), and
    the aircraft stays in the air."""
    s = fly("pitot_failure", at_s=19.22, duration_s=-1.0, params=["mode=zero"], flight_s=45.0, seed=392572427)
    assert_property(s, takeover_due=None)
    assert not s["verdict"]["aircraft_crashed"] and s["verdict"]["min_height_agl_ft"] > 100.0, s["_replay"]
    assert not any("STALL" in seg["why"] for seg in s["who_flew"]), s["_replay"]


def test_a_pitot_reading_low_below_the_stall_switch_speed_is_taken_over_at_once_and_flown_without_a_stall():
    """Mode low (x0.6: a cruise of 58 ft/s reads 35): at or below the stall switch speed, so the
    HA must take over in that period, for the stall or for the sensor, and then fly with the wing
    unstalled, trading no more than some tens of ft for the speed it believes it lacks."""
    s = fly("pitot_failure", at_s=12.0, duration_s=-1.0, params=["mode=low", "scale=0.6"], flight_s=30.0)
    assert_property(s, takeover_due=True)
    v = s["verdict"]
    assert v["stalled_from_fault_s"] == 0.0, (v, s["_replay"])
    assert v["min_height_agl_ft"] > 100.0, (v, s["_replay"])


def test_a_pitot_zeroed_before_the_wind_is_known_is_flown_on_pitch_and_power_not_on_the_tailwind():
    """The campaign's flight 63 (seed 22), at seed 6: the pitot zeroed 9 s after the launch in a
    4.7 m/s wind and moderate turbulence, a minute before the HA could know the wind. Flying the
    INS's speed over the ground, the HA believed the tailwind's excess, cut the throttle and the
    wing stalled 0.44 s (2.7 s at seed 1467205736). Without a speed it flies pitch and power:
    the attitude that holds the cruise speed whatever the wind, and the power for height."""
    s = fly("pitot_failure", at_s=9.45, duration_s=-1.0, params=["mode=zero"], flight_s=45.0, seed=6,
            extra=["--wind-mps", "4.67", "--wind-from-deg", "70.6", "--turbulence", "moderate"])
    assert_property(s, takeover_due=None)
    v = s["verdict"]
    assert v["stalled_from_fault_s"] == 0.0, (v, s["_replay"])
    assert v["min_height_agl_ft"] > 120.0, (v, s["_replay"])
