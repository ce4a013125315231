"""An HP that banks past the roll limit with valid commands is taken over inside S_x.

The HA switches on an inset of S_x (limits.yaml switch_region_fraction): the HP rolling out
slowly hands it an aircraft still inside S_x, and the roll it inherits while its controller slews
in from the HP's aileron stays inside too, so no takeover ever falls due on the truth. (Before
the inset, seed 11 peaked at 62.4 deg under the HA, 0.8 s outside S_x over three takeovers.)
The HA may take it for the stall first: at 54 deg of bank a level turn pulls 1.7 g, the stall
speed rises by sqrt(1.7), and the HA judges the stall by the load factor (issue 22 F1)."""
from stack_testing.fault_flight import assert_property, fly


def test_an_hp_banking_past_the_roll_limit_is_taken_over_before_the_limit():
    s = fly("bank", at_s=12.0, duration_s=-1.0, flight_s=35.0)
    assert_property(s, takeover_due=None)
    v = s["verdict"]
    assert v["hp_lost_control_s"] is not None, s["_replay"]
    assert any(seg["controller"] == "HA" and ("STATE_REGION" in seg["why"] or "STALL" in seg["why"])
               for seg in s["who_flew"]), s["_replay"]
    assert v["outside_S_x_from_fault_s"] == 0.0, s["_replay"]
