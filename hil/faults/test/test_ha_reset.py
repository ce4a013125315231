"""Issue 22, F5: the HA reset in flight (a watchdog or brown-out reset: its RAM afresh, its board's
retained words kept). It comes back with its home and its airborne latch, has a valid state again
at once (home cannot latch in flight), and hands the servos back to the healthy HP."""
from stack_testing.fault_flight import assert_property, fly


def test_an_ha_reset_in_flight_keeps_home_and_hands_back_to_the_hp():
    s = fly("ha_reset", at_s=20.0, duration_s=-1.0, flight_s=40.0)
    why = assert_property(s, takeover_due=None)
    d = s["fault"]["detail"]
    assert d["home_before"] and d["steps_after"] > 1000, why
    assert d["home_steps_after"] == d["steps_after"], why  # home in every period after the reset
    assert d["first_valid_s"] is not None and d["first_valid_s"] - d["reset_s"] <= 0.1, why
    assert d["valid_steps_after"] >= d["steps_after"] - 10, why
    assert d["hp_back_s"] is not None and d["hp_back_s"] - d["reset_s"] < 5.0, why
    assert s["verdict"]["recovery_s"] is not None and s["verdict"]["recovery_s"] < 5.0, why
    assert s["verdict"]["min_height_agl_ft"] > 100.0, why
