"""Trimmed starts: the JSBSim model trims where the LQR design trims, and holds level flight."""
import math
import os

import pytest
import yaml

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
from hil.fdm import Fdm, TrimError  # noqa: E402

AIRCRAFT = os.path.join(ROOT, "aircraft", "DG808")
FT = 0.3048


def design_trim():
    """The design trim the aircraft's checked-in gains were designed at."""
    with open(os.path.join(AIRCRAFT, "gains.yaml"), encoding="utf-8") as f:
        trim = yaml.safe_load(f)["trim"]
    return {k.upper(): float(trim[k]) for k in ("airspeed_m_s", "alpha_rad", "elevator_rad", "throttle")}


def test_trims_where_the_lqr_design_trims_at_the_design_point():
    d = design_trim()
    with Fdm(AIRCRAFT, seed=1) as fdm:
        # The design point is sea level, still air; 1 m up keeps the wheels off the ground.
        trim = fdm.reset_airborne(45.0, 8.0, 0.0, 1.0, 0.0, d["AIRSPEED_M_S"])
        truth = fdm.truth()
    assert truth.alpha_deg == pytest.approx(math.degrees(d["ALPHA_RAD"]), abs=0.02)
    assert trim.elevator_deg == pytest.approx(math.degrees(d["ELEVATOR_RAD"]), abs=0.02)
    assert trim.throttle == pytest.approx(d["THROTTLE"], abs=0.002)
    assert truth.servo == trim


def test_trimmed_start_holds_level_flight_for_30_s_with_no_input():
    with Fdm(AIRCRAFT, seed=1) as fdm:
        fdm.reset_airborne(47.4, 8.5, 420.0, 60.0, 135.0, 60.0 * FT)
        start = fdm.truth()
        worst = {"height": 0.0, "airspeed": 0.0, "pitch": 0.0, "roll": 0.0, "heading": 0.0, "vd": 0.0}
        for _ in range(300):
            fdm.advance(0.1)
            t = fdm.truth()
            worst["height"] = max(worst["height"], abs(t.height_agl_m - start.height_agl_m))
            worst["airspeed"] = max(worst["airspeed"], abs(t.airspeed_true_mps - start.airspeed_true_mps))
            worst["pitch"] = max(worst["pitch"], abs(t.pitch_deg - start.pitch_deg))
            worst["roll"] = max(worst["roll"], abs(t.roll_deg))
            worst["heading"] = max(worst["heading"], abs(t.heading_deg - start.heading_deg))
            worst["vd"] = max(worst["vd"], abs(t.vd_mps))
    assert t.t_s == pytest.approx(30.0)
    assert start.airspeed_true_mps == pytest.approx(60.0 * FT, abs=1e-6)
    assert start.heading_deg == pytest.approx(135.0, abs=1e-6)
    assert start.height_agl_m == pytest.approx(60.0, abs=1e-6)
    # Bands: well inside what the controller's own tolerances would notice.
    assert worst["height"] < 0.5, worst
    assert worst["airspeed"] < 0.1, worst
    assert worst["pitch"] < 0.2, worst
    assert worst["roll"] < 0.5, worst
    assert worst["heading"] < 1.0, worst
    assert worst["vd"] < 0.1, worst
    assert not t.on_ground


def test_level_flight_accelerometer_reads_one_g_up_and_mag_field_is_rotated_into_body():
    with Fdm(AIRCRAFT, seed=1, mag_field_ned_gauss=(0.2, 0.0, 0.45)) as fdm:
        fdm.reset_airborne(47.4, 8.5, 420.0, 100.0, 90.0, 20.0)
        fdm.advance(1.0)
        t = fdm.truth()
    ax, ay, az = t.accel_body_mps2
    theta = math.radians(t.pitch_deg)
    g = math.sqrt(ax * ax + ay * ay + az * az)
    assert g == pytest.approx(9.80, abs=0.03)          # local gravity, one g of lift+thrust
    assert az == pytest.approx(-g * math.cos(theta), abs=0.01)
    assert ax == pytest.approx(g * math.sin(theta), abs=0.01)
    assert abs(ay) < 0.01
    # Heading east, wings level: the field's north component lies along -y (left wing).
    mx, my, mz = t.mag_body_gauss
    assert my == pytest.approx(-0.2, abs=0.005)
    assert math.sqrt(mx * mx + my * my + mz * mz) == pytest.approx(math.hypot(0.2, 0.45), rel=1e-9)
    # Air data: ISA near 520 m MSL.
    assert t.pressure_pa == pytest.approx(95.2e3, rel=0.01)
    assert t.temperature_c == pytest.approx(11.6, abs=0.5)
    assert t.airspeed_cal_mps < t.airspeed_true_mps


def test_trim_below_the_stall_speed_is_refused_with_the_reason():
    with Fdm(AIRCRAFT, seed=1) as fdm:
        with pytest.raises(TrimError, match="stall"):
            fdm.reset_airborne(47.4, 8.5, 420.0, 100.0, 0.0, 35.0 * FT)
        # Nothing half-initialised is left to fly.
        with pytest.raises(RuntimeError, match="reset"):
            fdm.advance(0.1)
        with pytest.raises(ValueError, match="heading_deg"):
            fdm.reset_airborne(47.4, 8.5, 420.0, 100.0, math.nan, 18.0)


def test_airborne_start_with_the_wheels_in_the_ground_is_refused():
    with Fdm(AIRCRAFT, seed=1) as fdm:
        with pytest.raises(ValueError, match="reset_on_ground"):
            fdm.reset_airborne(47.4, 8.5, 420.0, 0.2, 0.0, 18.0)


def test_trim_faster_than_the_motor_can_hold_is_refused():
    with Fdm(AIRCRAFT, seed=1) as fdm:
        with pytest.raises(TrimError, match="throttle"):
            fdm.reset_airborne(47.4, 8.5, 420.0, 100.0, 0.0, 34.0)


def test_a_second_aircraft_is_a_new_folder(tmp_path):
    """Nothing of the DG808 is in the code: a copy with its own name and a heavier airframe
    generates its own model and trims where its own numbers say."""
    other = tmp_path / "XY99"
    other.mkdir()
    with open(os.path.join(AIRCRAFT, "airframe.yaml"), encoding="utf-8") as f:
        data = yaml.safe_load(f)
    data["aircraft"] = "XY99"
    data["mass_kg"] = 12.0
    (other / "airframe.yaml").write_text(yaml.safe_dump(data), encoding="utf-8")
    with open(os.path.join(AIRCRAFT, "limits.yaml"), encoding="utf-8") as f:
        (other / "limits.yaml").write_text(f.read(), encoding="utf-8")
    speed = 20.0
    alphas = {}
    for name, folder in (("DG808", AIRCRAFT), ("XY99", str(other))):
        with Fdm(folder, seed=1) as fdm:
            assert os.path.basename(fdm.model_path) == name + ".xml"
            fdm.reset_airborne(47.4, 8.5, 420.0, 100.0, 0.0, speed)
            alphas[name] = fdm.truth().alpha_deg
            fdm.advance(2.0)
            assert abs(fdm.truth().vd_mps) < 0.05
    # Lift ~ weight: CL(alpha) grows with the mass; the linear lift curve gives the alpha shift.
    a = data["aero"]
    cl_dg808 = a["cl0"] + a["cl_alpha_per_rad"] * math.radians(alphas["DG808"])
    expected = math.degrees((cl_dg808 * 12.0 / 9.0 - a["cl0"]) / a["cl_alpha_per_rad"])
    assert alphas["XY99"] == pytest.approx(expected, abs=0.1)


def test_model_goes_to_the_given_work_dir_and_stays_a_temporary_one_is_removed(tmp_path):
    with Fdm(AIRCRAFT, seed=1, work_dir=str(tmp_path)) as fdm:
        assert fdm.model_path == str(tmp_path / "aircraft" / "DG808" / "DG808.xml")
    assert os.path.isfile(fdm.model_path)
    with open(fdm.model_path, encoding="utf-8") as f:
        assert "GENERATED by hil/fdm/model_xml.py" in f.read()
    with Fdm(AIRCRAFT, seed=1) as fdm:
        temporary = fdm.model_path
        assert os.path.isfile(temporary)
    assert not os.path.exists(temporary)
