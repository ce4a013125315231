"""On the ground: a parked start sits on its wheels and stays put, throttle rolls it along its
heading, the rudder steers the nose wheel, and it can take off."""
import math
import os

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
from hil.fdm import Fdm, Surfaces, Wind  # noqa: E402

AIRCRAFT = os.path.join(ROOT, "aircraft", "DG808")


def test_parked_start_rests_on_its_wheels():
    with Fdm(AIRCRAFT, seed=2) as fdm:
        fdm.reset_on_ground(47.4, 8.5, 420.0, 270.0)
        start = fdm.truth()
        wheel_z = max(c.z_m for c in fdm.airframe.contacts if c.kind == "BOGEY")
        fdm.advance(10.0)
        end = fdm.truth()
    for t in (start, end):
        assert t.on_ground
        # CG a little under the wheels' unloaded height: the tyres carry the weight.
        assert wheel_z - 0.05 < t.height_agl_m < wheel_z
        assert t.ground_msl_m == pytest.approx(420.0, abs=1e-6)
        assert t.alt_msl_m == pytest.approx(t.ground_msl_m + t.height_agl_m, abs=1e-6)
        assert abs(t.pitch_deg) < 2.0 and abs(t.roll_deg) < 0.1
        assert math.sqrt(sum(a * a for a in t.accel_body_mps2)) == pytest.approx(9.80, abs=0.03)
        assert t.accel_body_mps2[2] < -9.7
        assert t.servo == Surfaces(0.0, 0.0, 0.0, 0.0)
    assert start.t_s == 0.0 and end.t_s == pytest.approx(10.0)
    assert end.height_agl_m == pytest.approx(start.height_agl_m, abs=1e-3)
    assert math.hypot(end.vn_mps, end.ve_mps) < 1e-3 and abs(end.vd_mps) < 1e-3
    assert end.lat_deg == pytest.approx(47.4, abs=1e-8) and end.lon_deg == pytest.approx(8.5, abs=1e-8)
    assert end.heading_deg == pytest.approx(270.0, abs=0.01)


def test_a_glider_parked_crosswind_in_a_strong_gust_is_held_upright_by_its_crew():
    # Flight 15 of a 16-flight campaign (seed 102, faults at 3-6 s): heading 82 deg for its first
    # waypoint, the wind from 347 deg at 9.2 m/s with moderate turbulence. Left alone while it
    # settled, the wing lifted, it rolled on its back and JSBSim's state went NaN, the flight's
    # truth and sensors with it.
    with Fdm(AIRCRAFT, seed=721717211, wind=Wind(346.8, 9.22, "moderate"),
             temperature_deviation_c=0.0) as fdm:
        fdm.reset_on_ground(38.95, -95.26, 260.0, 81.87, held=True)
        start = fdm.truth()
        fdm.advance(5.0)
        end = fdm.truth()
    for t in (start, end):
        assert all(math.isfinite(v) for v in (t.lat_deg, t.lon_deg, t.height_agl_m, t.roll_deg, t.pitch_deg))
        assert t.on_ground and abs(t.roll_deg) <= 3.5 and abs(t.pitch_deg) <= 3.5
    assert end.lat_deg == pytest.approx(38.95, abs=1e-5) and end.lon_deg == pytest.approx(-95.26, abs=1e-5)


def rolled(heading_deg, surfaces, seconds):
    """The truth after seconds on the ground from a parked start facing heading_deg, surfaces held."""
    with Fdm(AIRCRAFT, seed=2) as fdm:
        fdm.reset_on_ground(47.4, 8.5, 420.0, heading_deg)
        fdm.set_surfaces(surfaces)
        fdm.advance(seconds)
        return fdm.truth()


def test_full_throttle_rolls_it_along_its_heading_on_the_wheels():
    t = rolled(270.0, Surfaces(0.0, 0.0, 0.0, 1.0), 5.0)
    assert t.on_ground
    assert t.ve_mps < -5.0 and abs(t.vn_mps) < 0.1       # westward, straight
    assert t.airspeed_true_mps == pytest.approx(math.hypot(t.vn_mps, t.ve_mps), abs=0.01)
    assert t.heading_deg == pytest.approx(270.0, abs=1.0)


def test_positive_rudder_steers_the_nose_wheel_left():
    t = rolled(0.0, Surfaces(0.0, 0.0, 8.0, 0.6), 2.0)
    assert t.on_ground
    assert t.r_rad_s < -0.2
    assert 270.0 < t.heading_deg < 358.0


def test_takes_off_from_the_runway_in_a_crosswind_with_simple_loops():
    """What the HiL's take-off needs from the model: roll, rotate, lift off, climb, no crash."""
    with Fdm(AIRCRAFT, seed=2, wind=Wind(300.0, 4.0, "light")) as fdm:
        fdm.reset_on_ground(47.4, 8.5, 420.0, 270.0)
        fdm.set_surfaces(Surfaces(0.0, 0.0, 0.0, 1.0))
        liftoff = None
        while fdm.truth().t_s < 40.0:
            t = fdm.truth()
            heading_error = (t.heading_deg - 270.0 + 180.0) % 360.0 - 180.0
            if t.on_ground:
                elevator = -3.0 if t.airspeed_true_mps > 15.0 else 0.0
            else:
                liftoff = liftoff if liftoff is not None else t
                elevator = max(-10.0, min(10.0, t.pitch_deg - 8.0))
            fdm.set_surfaces(Surfaces(elevator, -0.5 * t.roll_deg, 2.0 * heading_error, 1.0))
            fdm.advance(0.1)
        t = fdm.truth()
    assert liftoff is not None and liftoff.t_s < 20.0
    assert liftoff.airspeed_true_mps > 42.0 * 0.3048            # above the stall speed
    assert t.height_agl_m > 30.0 and not t.on_ground and not t.crashed
    assert t.heading_deg == pytest.approx(270.0, abs=10.0)
