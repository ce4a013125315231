"""HP controller crash (SIGKILL): the HA has the servos within one period of the deadline, asks for
a restart, and the restarted HP gets control back."""
from stack_testing.fault_flight import assert_property, fly


def test_a_killed_controller_is_replaced_by_the_ha_then_restarted_and_given_back_control():
    s = fly("crash", at_s=15.0)
    assert_property(s, takeover_due=True)
    assert s["verdict"]["recovery_s"] is not None, s["_replay"]
