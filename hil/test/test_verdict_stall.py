"""The verdict judges the stall on the truth (hil/verdicts.py): time with the true angle of
attack past the airframe's stall while the HA flies, and the height a recovery cost, from a
takeover to the lowest point before the aircraft climbs again."""
import os
from collections import namedtuple

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
from hil import verdicts  # noqa: E402
from hil.flight_record import Period  # noqa: E402
from hil.fdm.airframe import Airframe  # noqa: E402

M = namedtuple("M", "alpha_deg height_above_home_ft on_ground")
R = namedtuple("R", "controller")


def recs(samples):
    """(t_s, controller, height, alpha) -> the simulator's records."""
    return [Period(int(round(t * 1e6)), M(a, h, False), R(c), None, 60.0) for t, c, h, a in samples]


def test_the_stall_alpha_is_the_airframes_and_a_stall_is_past_either_side():
    a_s, a_n = verdicts.stall_alphas_deg(Airframe(os.path.join(ROOT, "aircraft", "DG808")))
    assert round(a_s, 2) == 8.85 and a_n < 0.0                       # (cl_max - cl0) / cl_alpha
    assert verdicts.stalled(M(8.9, 100.0, False), (a_s, a_n)) and verdicts.stalled(M(a_n - 0.1, 100.0, False), (a_s, a_n))
    assert not verdicts.stalled(M(8.8, 100.0, False), (a_s, a_n))
    assert not verdicts.stalled(M(20.0, 0.0, True), (a_s, a_n))        # on its wheels: not flying


def test_a_recovery_costs_the_height_from_the_takeover_to_the_lowest_point_before_climbing_again():
    # HP at 200 ft, the HA takes over at 1 s, sinks to 170 ft, climbs back to 190, hands back.
    heights = [200, 200, 195, 185, 175, 170, 171, 172, 175, 180, 190, 190]
    ctrl = [0, 1, 1, 1, 1, 2, 2, 2, 2, 2, 2, 0]
    losses = verdicts.recovery_height_losses(recs([(0.5 * i, c, h, 3.0) for i, (c, h) in enumerate(zip(ctrl, heights))]), 0.0)
    assert losses == [(0.5, 30.0, True)]
    # A takeover before since_s does not count; one that never climbs again never recovered.
    sinking = recs([(0.5 * i, c, 200 - 10 * i, 3.0) for i, c in enumerate([0, 1, 1, 3, 3])])
    assert verdicts.recovery_height_losses(sinking, 1.0) == []
    assert verdicts.recovery_height_losses(sinking, 0.0) == [(0.5, 30.0, False)]


def test_the_longest_stall_under_the_ha_tells_a_gust_from_a_stall_held():
    alphas = (8.85, -5.0)
    spikes = recs([(0.01 * i, 1, 200.0, 9.5 if i in (3, 7) else 3.0) for i in range(20)])
    held = recs([(0.01 * i, 2, 200.0, 12.0 if 5 <= i < 15 else 3.0) for i in range(20)])
    under_hp = recs([(0.01 * i, 0, 200.0, 12.0) for i in range(20)])
    assert round(verdicts.longest_stall_s(spikes, alphas, 0.01), 6) == 0.01
    assert round(verdicts.longest_stall_s(held, alphas, 0.01), 6) == 0.1
    assert verdicts.longest_stall_s(under_hp, alphas, 0.01) == 0.0


def test_a_stall_the_aircraft_was_launched_into_is_the_launchs_and_ends_with_the_first_flying_period():
    # The airborne start in a gust: stalled for the first 8 periods, then flying; a later stall is
    # not the launch's however it began.
    alphas = (8.85, -5.0)
    launched = recs([(2.0 + 0.01 * i, 1, 200.0, 11.9 if i < 8 or 30 <= i < 33 else 3.0) for i in range(40)])
    assert verdicts.launch_stall_periods(launched, alphas) == 8
    assert verdicts.launch_stall_periods(launched[1:], alphas) == 7
    assert verdicts.launch_stall_periods(launched[8:], alphas) == 0
    flying = recs([(2.0 + 0.01 * i, 1, 200.0, 3.0) for i in range(5)])
    assert verdicts.launch_stall_periods(flying, alphas) == 0
