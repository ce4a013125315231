"""The stall: pulling the elevator up past cl_max at the trim throttle loses lift, and the stall
speed measured in flight agrees with limits.yaml's stall_speed_ftps."""
import dataclasses
import math
import os
import statistics

import pytest
import yaml

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
from hil.fdm import Fdm  # noqa: E402
from hil.fdm.airframe import Airframe  # noqa: E402

AIRCRAFT = os.path.join(ROOT, "aircraft", "DG808")
FT = 0.3048
R_AIR = 287.053            # J/(kg K), dry air
RHO_SEA_LEVEL = 1.225      # ISA, where limits.yaml's 1 g stall speed is stated
G0 = 9.80665


def lift_coefficient(truth, mass_kg, area_m2):
    """CL as a flight test measures it: accelerometer, air data and the weighed aircraft."""
    rho = truth.pressure_pa / (R_AIR * (truth.temperature_c + 273.15))
    alpha = math.radians(truth.alpha_deg)
    ax, _, az = truth.accel_body_mps2
    lift = mass_kg * (-az * math.cos(alpha) + ax * math.sin(alpha))
    return lift / (0.5 * rho * truth.airspeed_true_mps ** 2 * area_m2)


@pytest.fixture(scope="module")
def pull_up():
    """From trim, elevator up at 0.5 deg/s to full travel, trim throttle held; 10 Hz samples."""
    with Fdm(AIRCRAFT, seed=5) as fdm:
        trim = fdm.reset_airborne(47.4, 8.5, 420.0, 300.0, 0.0, 18.0)
        limit = fdm.airframe.servos["elevator"].limit_deg
        samples = []
        while fdm.truth().t_s < 40.0:
            de = max(trim.elevator_deg - 0.5 * fdm.truth().t_s, -limit)
            fdm.set_surfaces(dataclasses.replace(trim, elevator_deg=de))
            fdm.advance(0.1)
            samples.append(fdm.truth())
        yield fdm.airframe, trim, samples


def test_pulling_past_cl_max_stalls_and_the_aircraft_sinks(pull_up):
    af, trim, samples = pull_up
    cls = [lift_coefficient(s, af.mass_kg, af.wing_area_m2) for s in samples]
    i_peak = max(range(len(cls)), key=cls.__getitem__)
    alpha_stall_deg = math.degrees(af.alpha_stall_rad)
    # Lift peaks at the stall angle, then the wing is driven well past it.
    assert samples[i_peak].alpha_deg == pytest.approx(alpha_stall_deg, abs=1.0)
    assert max(s.alpha_deg for s in samples) > alpha_stall_deg + 8.0
    # Past the stall lift has gone: the last 10 s fly at well under cl_max, sinking fast.
    late = samples[-100:]
    assert statistics.median(cls[-100:]) < 0.8 * cls[i_peak]
    assert min(s.vd_mps for s in late) > 3.0
    assert all(s.throttle == trim.throttle for s in (x.servo for x in samples))
    peak_height = max(s.height_agl_m for s in samples)
    assert peak_height - samples[-1].height_agl_m > 30.0


def test_held_in_the_stall_it_drops_a_wing(pull_up):
    """Past the stall the down-going wing loses lift: roll damping turns to autorotation."""
    af, _, samples = pull_up
    alpha_stall_deg = math.degrees(af.alpha_stall_rad)
    first_stall = next(i for i, s in enumerate(samples) if s.alpha_deg > alpha_stall_deg)
    assert max(abs(s.roll_deg) for s in samples[:first_stall]) < 1.0      # wings level up to it
    assert max(abs(s.roll_deg) for s in samples[first_stall:]) > 30.0


def test_measured_stall_speed_agrees_with_limits_yaml(pull_up):
    af, _, samples = pull_up
    cl_max_measured = max(lift_coefficient(s, af.mass_kg, af.wing_area_m2) for s in samples)
    # Trimmed at the stall, the elevator's own download takes a little off the wing's cl_max.
    assert cl_max_measured == pytest.approx(af.aero["cl_max"], rel=0.03)
    v_stall_ftps = math.sqrt(2.0 * af.mass_kg * G0 / (RHO_SEA_LEVEL * af.wing_area_m2 * cl_max_measured)) / FT
    with open(os.path.join(AIRCRAFT, "limits.yaml"), encoding="utf-8") as f:
        limit_ftps = yaml.safe_load(f)["state"]["stall_speed_ftps"]
    assert v_stall_ftps == pytest.approx(limit_ftps, rel=0.03)


def test_the_wing_drop_is_a_spin_entry_not_a_snap_roll(pull_up):
    """Autorotation lasts only while the down-going wing is on the lift break: strip theory over
    the lift curve bounds the roll rate. Held in this deep stall the old model (a linear cl_p
    times the local lift slope) spun at 363 deg/s, and in HiL flights snapped at 1,000 deg/s just
    past the stall; strip theory spins at 240 deg/s here, a model sailplane's spin."""
    _, _, samples = pull_up
    assert max(abs(math.degrees(s.p_rad_s)) for s in samples) < 300.0


@pytest.mark.parametrize("alpha_deg", [-4.0, 0.0, 2.0, 5.0])
def test_roll_damping_in_attached_flow_is_the_linear_cl_p(alpha_deg):
    af = Airframe(AIRCRAFT)
    # The tip stays short of the stall: the strip integral is cl_p's own p b/2V.
    assert af.roll_damping_phat(alpha_deg, 0.02) == pytest.approx(0.02, rel=0.01)


def test_roll_damping_past_the_stall_autorotates_at_low_rates_and_damps_at_high_ones():
    af = Airframe(AIRCRAFT)
    alpha_deg = math.degrees(af.alpha_stall_rad) + 1.5
    assert af.roll_damping_phat(alpha_deg, 0.02) < 0.0     # the down-going wing loses lift
    assert af.roll_damping_phat(alpha_deg, 0.3) > 0.0      # its tip is past the break: damped again
    assert af.roll_damping_phat(alpha_deg, -0.3) == pytest.approx(-af.roll_damping_phat(alpha_deg, 0.3))


def test_the_models_roll_damping_table_is_the_strip_integral_at_its_breakpoints():
    """The JSBSim table is computed for the whole grid at once: each breakpoint must be the strip
    integral itself, to the bit (a flight's truth is compared byte for byte), on every row around
    both stalls, where the table bends, and on every third row elsewhere."""
    af = Airframe(AIRCRAFT)
    alphas, phats, rows = af.roll_damping_grid()
    stalls = (math.degrees(af.alpha_stall_rad), math.degrees(af.alpha_stall_neg_rad))
    checked = 0
    for i, alpha_deg in enumerate(alphas):
        if i % 3 and min(abs(alpha_deg - s) for s in stalls) > af.stall_drop_deg + 2.0:
            continue
        for j, phat in enumerate(phats):
            assert rows[i][j] == af.roll_damping_phat(alpha_deg, phat), (alpha_deg, phat)
            checked += 1
    assert checked >= len(alphas) * len(phats) // 3
