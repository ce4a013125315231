"""An HP that banks past the roll limit with valid commands is taken over."""
from flight import assert_property, fly


def test_an_hp_banking_past_the_roll_limit_is_taken_over():
    s = fly("bank", at_s=12.0, duration_s=-1.0, flight_s=35.0)
    assert_property(s, takeover_due=True)
