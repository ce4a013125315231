"""VN-200 link loss on the HP side: the HP reports its sensor link down and the HA takes over
within one period of that command."""
from stack_testing.fault_flight import assert_property, fly


def test_losing_the_hps_vn200_hands_the_servos_to_the_ha():
    s = fly("hp_vn200_loss", at_s=15.0, duration_s=5.0)
    assert_property(s, takeover_due=True)
