"""Estimator divergence: alpha/beta estimates running away are taken over the period they pass
their limit."""
from stack_testing.fault_flight import assert_property, fly


def test_runaway_alpha_beta_estimates_hand_the_servos_to_the_ha():
    s = fly("divergence", at_s=15.0, duration_s=4.0, params=["rate_deg_s=20"])
    assert_property(s, takeover_due=True)
