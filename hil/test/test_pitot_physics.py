"""The pitot's physics and the air it flies in (hil/sensors.py, hil/fdm): the AMS5812 reads the
relative wind's component along the probe, with the FDM's density, so sideslip and high alpha
read low, air from behind reads nothing, and IAS falls below TAS at altitude and on a hot day;
the wind can change in flight."""
import dataclasses
import math
import os

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
from hil import sensors  # noqa: E402
from hil.fdm import Fdm, Wind  # noqa: E402

AIRCRAFT = os.path.join(ROOT, "aircraft", "DG808")


def trimmed(ground_m=260.0, **kw):
    fdm = Fdm(AIRCRAFT, seed=1, **kw)
    fdm.reset_airborne(38.95, -95.26, ground_m, 61.0, 90.0, 18.288)
    return fdm


def test_the_probe_reads_the_calibrated_airspeed_along_it_and_less_off_axis():
    with trimmed() as fdm:
        t = fdm.truth()
    level = dataclasses.replace(t, alpha_deg=0.0, beta_deg=0.0)
    assert sensors.probe_airspeed_mps(level) == t.airspeed_cal_mps     # as before: exactly vc
    high_alpha = dataclasses.replace(t, alpha_deg=14.0, beta_deg=0.0)
    slip = dataclasses.replace(t, alpha_deg=0.0, beta_deg=20.0)
    assert sensors.probe_airspeed_mps(high_alpha) == pytest.approx(t.airspeed_cal_mps * math.cos(math.radians(14.0)))
    assert sensors.probe_airspeed_mps(slip) == pytest.approx(t.airspeed_cal_mps * math.cos(math.radians(20.0)))
    behind = dataclasses.replace(t, alpha_deg=0.0, beta_deg=180.0)
    assert sensors.probe_airspeed_mps(behind) == 0.0                   # tail to the wind: nothing


def test_a_hot_day_at_a_high_field_reads_the_pitot_below_the_true_airspeed():
    with trimmed(ground_m=0.0) as sea, trimmed(ground_m=6500.0 * 0.3048, temperature_deviation_c=20.0) as hot:
        a, b = sea.truth(), hot.truth()
    assert a.airspeed_true_mps == pytest.approx(b.airspeed_true_mps, abs=0.01)
    assert a.air_density_kg_m3 == pytest.approx(1.225, rel=0.01)
    # ISA at 6,700 ft is 0.82 of sea level's density, 20 C hotter some 7 % less again.
    assert b.air_density_kg_m3 == pytest.approx(1.225 * 0.818 * 0.932, rel=0.02)
    ias_tas = sensors.probe_airspeed_mps(b) / b.airspeed_true_mps
    assert ias_tas == pytest.approx(math.sqrt(b.air_density_kg_m3 / 1.225), rel=0.01)
    assert ias_tas < 0.9 < sensors.probe_airspeed_mps(a) / a.airspeed_true_mps


def test_a_tailwind_set_in_flight_takes_the_airspeed_at_once_and_not_the_ground_speed():
    with trimmed() as fdm:
        fdm.advance(1.0)
        before = fdm.truth()
        fdm.set_wind(Wind(mean_from_deg=270.0, mean_mps=5.0))   # heading east: from behind
        fdm.advance(0.01)
        after = fdm.truth()
        assert after.ve_mps == pytest.approx(before.ve_mps, abs=0.05)
        assert after.airspeed_true_mps == pytest.approx(before.airspeed_true_mps - 5.0, abs=0.1)
        fdm.set_wind(Wind(mean_from_deg=270.0, mean_mps=5.0, turbulence="moderate"))
        speeds = []
        for _ in range(100):
            fdm.advance(0.05)
            speeds.append(fdm.truth().airspeed_true_mps)
    assert max(speeds) - min(speeds) > 0.5                         # the gusts came on with it
