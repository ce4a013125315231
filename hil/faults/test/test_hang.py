"""HP controller hang (SIGSTOP, never continued): the HA flies, hp_supervisor kills the hung
process and starts a new one, the HA hands control back."""
from stack_testing.fault_flight import assert_property, fly


def test_a_hung_controller_never_continued_is_replaced_by_the_ha_and_restarted():
    s = fly("hang", at_s=15.0, duration_s=-1.0)
    assert_property(s, takeover_due=True)
    assert s["verdict"]["recovery_s"] is not None, s["_replay"]
