"""Issue 22 F1 in closed loop: an HP that pulls in a 45 deg bank stalls the wing at about 70 ft/s
and nearly 3 g, far above the HA's 46.2 ft/s stall switch speed (hil/faults/accelerated_stall.py).
A stall judged by airspeed alone never sees it: on 0da675b the wing stalled with the HP flying
(seed 11: at 20.10 s), the HA took over 8 periods later for the departure (STATE_REGION) and flew
1.94 s with the wing stalled itself. The HA must take the servos before the wing stalls (the
class's takeover due: the truth's alpha past the airframe's stall while the HP flies), so the
wing never stalls, whoever flies. What it took (seed 11, 0.5 to 1.8 s stalled under the HA on the
way): the load factor from the gyros (V q / g on top of cos(bank): the pull shows before the
alpha), a pull released at the servo's rate on the takeover, and the HA's own pitch loop held
below 0.7 of the wing's maximum lift."""
from stack_testing.fault_flight import assert_property, fly


def test_an_hp_pulling_into_an_accelerated_stall_in_a_banked_turn_is_taken_over_before_the_wing_stalls():
    s = fly("accelerated_stall", at_s=12.0, duration_s=-1.0, flight_s=30.0)
    v = s["verdict"]
    assert v["hp_lost_control_s"] is not None, s["_replay"]          # the HA took the servos
    assert v["stalled_from_fault_s"] == 0.0, (v, s["_replay"])         # before the wing stalled
    assert v["stalled_under_ha_s"] == 0.0, (v, s["_replay"])
    assert v["min_airspeed_margin_ftps"] > 4.2, (v, s["_replay"])     # never near the 1 g switch speed
    assert_property(s, takeover_due=None)
