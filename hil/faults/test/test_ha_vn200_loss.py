"""VN-200 loss on the HA side: the HA cannot judge the state, so it takes the servos within one
period of its state going stale, and flies inside S_x."""
from flight import assert_property, fly


def test_losing_the_has_own_vn200_hands_it_the_servos():
    s = fly("ha_vn200_loss", at_s=15.0, duration_s=3.0)
    assert_property(s, takeover_due=True)
