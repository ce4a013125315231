"""Surface sign conventions (msg/pwm.msg) reach the airframe the right way round, and the servo
model delays, rate-limits and clips what it is told."""
import dataclasses
import math
import os

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
from hil.fdm import Fdm  # noqa: E402

AIRCRAFT = os.path.join(ROOT, "aircraft", "DG808")


@pytest.fixture
def trimmed():
    with Fdm(AIRCRAFT, seed=3) as fdm:
        trim = fdm.reset_airborne(47.4, 8.5, 420.0, 100.0, 0.0, 18.0)
        yield fdm, trim


def respond(fdm, trim, seconds=0.5, **delta):
    cmd = dataclasses.replace(trim, **{k: getattr(trim, k) + v for k, v in delta.items()})
    start = fdm.truth()
    fdm.set_surfaces(cmd)
    fdm.advance(seconds)
    return start, fdm.truth()


def test_positive_elevator_trailing_edge_down_pitches_nose_down(trimmed):
    start, end = respond(*trimmed, elevator_deg=5.0)
    assert end.q_rad_s < -0.1
    assert end.pitch_deg < start.pitch_deg - 1.0


def test_negative_elevator_pitches_nose_up(trimmed):
    start, end = respond(*trimmed, elevator_deg=-5.0)
    assert end.q_rad_s > 0.1
    assert end.pitch_deg > start.pitch_deg + 1.0


def test_positive_aileron_rolls_right(trimmed):
    _, end = respond(*trimmed, aileron_deg=5.0)
    assert end.p_rad_s > 0.1
    assert end.roll_deg > 2.0


def test_negative_aileron_rolls_left(trimmed):
    _, end = respond(*trimmed, aileron_deg=-5.0)
    assert end.p_rad_s < -0.1
    assert end.roll_deg < -2.0


def test_positive_rudder_trailing_edge_left_yaws_left(trimmed):
    start, end = respond(*trimmed, rudder_deg=5.0)
    assert end.r_rad_s < -0.05
    heading_change = (end.heading_deg - start.heading_deg + 180.0) % 360.0 - 180.0
    assert heading_change < -0.5
    assert end.beta_deg > 0.5          # nose left of the airflow: wind from the right


def test_more_throttle_accelerates_forward(trimmed):
    start, end = respond(*trimmed, seconds=1.0, throttle=0.5)
    assert end.accel_body_mps2[0] > start.accel_body_mps2[0] + 0.5
    assert end.airspeed_true_mps > start.airspeed_true_mps + 0.2


def test_servo_waits_its_delay_then_moves_at_its_rate_and_stops_at_its_travel(trimmed):
    fdm, trim = trimmed
    af = fdm.airframe
    rate = af.servos["elevator"].rate_per_s
    delay_s = af.servo_delay_s
    limit = af.servos["elevator"].limit_deg
    fdm.set_surfaces(dataclasses.replace(trim, elevator_deg=45.0))
    fdm.advance(round(delay_s / fdm.dt_s) * fdm.dt_s)
    assert fdm.truth().servo.elevator_deg == trim.elevator_deg       # still in the delay line
    fdm.advance(2 * fdm.dt_s)
    moved = fdm.truth().servo.elevator_deg - trim.elevator_deg
    assert moved == pytest.approx(2 * fdm.dt_s * rate, rel=1e-9)     # rate limited
    fdm.advance(0.5)
    assert fdm.truth().servo.elevator_deg == limit                   # clipped to the travel
    # The other servos held still meanwhile.
    assert fdm.truth().servo.aileron_deg == 0.0
    assert fdm.truth().servo.throttle == trim.throttle


def test_throttle_is_clipped_to_zero_one(trimmed):
    fdm, trim = trimmed
    fdm.set_surfaces(dataclasses.replace(trim, throttle=-1.0))
    fdm.advance(1.0)
    assert fdm.truth().servo.throttle == 0.0
    fdm.set_surfaces(dataclasses.replace(trim, throttle=3.0))
    fdm.advance(1.0)
    assert fdm.truth().servo.throttle == 1.0


def test_advance_takes_whole_steps_only(trimmed):
    fdm, _ = trimmed
    fdm.advance(0.01)
    assert fdm.truth().t_s == pytest.approx(0.01)
    with pytest.raises(ValueError, match="whole number"):
        fdm.advance(0.0123)
    with pytest.raises(ValueError, match="finite"):
        fdm.set_surfaces(dataclasses.replace(fdm.truth().servo, elevator_deg=math.nan))
