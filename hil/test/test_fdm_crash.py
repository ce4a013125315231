"""Touching the ground: a gentle landing rolls out on the wheels; flying into it ends the flight
with FdmCrash and a reason, never with NaNs."""
import math
import os

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
from hil.fdm import Fdm, FdmCrash, Surfaces  # noqa: E402

AIRCRAFT = os.path.join(ROOT, "aircraft", "DG808")


def test_gentle_glide_onto_the_runway_lands_and_rolls_out_on_the_wheels():
    with Fdm(AIRCRAFT, seed=4) as fdm:
        trim = fdm.reset_airborne(47.4, 8.5, 420.0, 3.0, 60.0, 16.0)
        fdm.set_surfaces(Surfaces(trim.elevator_deg, 0.0, 0.0, 0.0))     # motor off
        worst_sink = 0.0
        while not fdm.truth().on_ground:
            assert fdm.truth().t_s < 20.0, "never touched down"
            fdm.advance(0.05)
            worst_sink = max(worst_sink, fdm.truth().vd_mps)
        touchdown = fdm.truth()
        fdm.advance(5.0)
        t = fdm.truth()
    assert 0.5 < worst_sink < fdm.airframe.crash_sink_mps
    assert t.on_ground and not t.crashed and fdm.crash_reason is None
    assert t.airspeed_true_mps < touchdown.airspeed_true_mps      # slowing on the wheels
    assert abs(t.vd_mps) < 0.05 and abs(t.roll_deg) < 1.0
    assert t.heading_deg == pytest.approx(60.0, abs=2.0)


def test_diving_into_the_ground_ends_the_flight_with_a_reason():
    with Fdm(AIRCRAFT, seed=4) as fdm:
        fdm.reset_airborne(47.4, 8.5, 420.0, 50.0, 0.0, 18.0)
        fdm.set_surfaces(Surfaces(15.0, 0.0, 0.0, 1.0))                 # full nose down
        with pytest.raises(FdmCrash, match="sinking"):
            fdm.advance(30.0)
        wreck = fdm.truth()
        assert wreck.crashed and wreck.on_ground
        assert wreck.t_s < 10.0
        assert all(math.isfinite(x) for x in (wreck.height_agl_m, wreck.vd_mps, wreck.pitch_deg))
        assert fdm.crash_reason.startswith("crashed at t = ")
        # The flight is over until the next reset.
        with pytest.raises(FdmCrash):
            fdm.advance(0.1)
        assert fdm.truth() == wreck
        fdm.reset_airborne(47.4, 8.5, 420.0, 50.0, 0.0, 18.0)
        fdm.advance(1.0)
        assert not fdm.truth().crashed and fdm.crash_reason is None
