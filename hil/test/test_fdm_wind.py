"""Wind: ground speed is air speed plus the wind; turbulence shakes the air speed as its level says."""
import math
import os
import statistics

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
from hil.fdm import Fdm, Wind  # noqa: E402

AIRCRAFT = os.path.join(ROOT, "aircraft", "DG808")


def test_wind_from_the_north_adds_a_southward_ground_velocity():
    with Fdm(AIRCRAFT, seed=1, wind=Wind(mean_from_deg=0.0, mean_mps=5.0)) as fdm:
        fdm.reset_airborne(47.4, 8.5, 420.0, 100.0, 90.0, 18.0)     # heading east
        for t in (fdm.truth(), (fdm.advance(2.0), fdm.truth())[1]):
            assert t.airspeed_true_mps == pytest.approx(18.0, abs=0.02)
            assert t.ve_mps == pytest.approx(18.0, abs=0.05)
            assert t.vn_mps == pytest.approx(-5.0, abs=0.05)
            assert t.heading_deg == pytest.approx(90.0, abs=0.2)
            assert abs(t.beta_deg) < 0.1            # trimmed in the air mass: no sideslip


def test_headwind_slows_the_ground_speed_not_the_air_speed():
    with Fdm(AIRCRAFT, seed=1, wind=Wind(mean_from_deg=180.0, mean_mps=7.0)) as fdm:
        fdm.reset_airborne(47.4, 8.5, 420.0, 100.0, 180.0, 18.0)    # heading south, into it
        fdm.advance(5.0)
        t = fdm.truth()
    assert t.airspeed_true_mps == pytest.approx(18.0, abs=0.05)
    assert -t.vn_mps == pytest.approx(18.0 - 7.0, abs=0.1)
    assert abs(t.ve_mps) < 0.1


@pytest.mark.parametrize("seed", range(8))
def test_an_airborne_start_in_turbulence_flies_at_its_trim_airspeed_in_the_air_where_it_starts(seed):
    """The gust at the start point is part of the air the aircraft is launched in: the start is
    the trim airspeed and angle of attack in that air, not in the mean wind (which left a step of
    up to 16 ft/s and 13 deg for the first period to meet: a campaign's cold start launched at
    1.04 times the stall speed and stalled under the HA a second later)."""
    with Fdm(AIRCRAFT, seed=seed, wind=Wind(mean_from_deg=277.6, mean_mps=5.2)) as calm:
        calm.reset_airborne(47.4, 8.5, 420.0, 61.0, 82.0, 18.3)
        trim_alpha_deg = calm.truth().alpha_deg
    with Fdm(AIRCRAFT, seed=seed, wind=Wind(mean_from_deg=277.6, mean_mps=5.2, turbulence="moderate")) as fdm:
        fdm.reset_airborne(47.4, 8.5, 420.0, 61.0, 82.0, 18.3)
        start = fdm.truth()
        fdm.advance(0.01)
        first = fdm.truth()
    assert start.airspeed_true_mps == pytest.approx(18.3, abs=0.01)
    assert start.alpha_deg == pytest.approx(trim_alpha_deg, abs=0.01)
    assert first.airspeed_true_mps == pytest.approx(18.3, abs=0.15)   # one period of gusts
    assert first.alpha_deg == pytest.approx(trim_alpha_deg, abs=1.0)


def airspeed_spread(turbulence):
    with Fdm(AIRCRAFT, seed=9, wind=Wind(mean_from_deg=200.0, mean_mps=4.0, turbulence=turbulence)) as fdm:
        fdm.reset_airborne(47.4, 8.5, 420.0, 100.0, 0.0, 18.0)
        speeds = []
        for _ in range(200):
            fdm.advance(0.1)
            speeds.append(fdm.truth().airspeed_true_mps)
    return statistics.pstdev(speeds)


def test_turbulence_level_orders_the_airspeed_spread():
    none, light, moderate = (airspeed_spread(x) for x in ("none", "light", "moderate"))
    assert none < 0.02
    assert light > 0.1
    assert moderate > 1.5 * light


def test_unknown_turbulence_level_is_rejected():
    with pytest.raises(ValueError, match="turbulence"):
        Wind(mean_from_deg=0.0, mean_mps=3.0, turbulence="severe")


def test_position_moves_with_the_ground_velocity():
    """lat/lon change as the NED velocity says (WGS84 radii), so north/east from home agree."""
    a, e2 = 6378137.0, 6.69437999014e-3
    with Fdm(AIRCRAFT, seed=1, wind=Wind(mean_from_deg=0.0, mean_mps=5.0)) as fdm:
        fdm.reset_airborne(47.4, 8.5, 420.0, 100.0, 90.0, 18.0)
        start = fdm.truth()
        fdm.advance(10.0)
        end = fdm.truth()
    lat = math.radians(start.lat_deg)
    w = 1.0 - e2 * math.sin(lat) ** 2
    north_m = math.radians(end.lat_deg - start.lat_deg) * a * (1.0 - e2) / w ** 1.5
    east_m = math.radians(end.lon_deg - start.lon_deg) * a / math.sqrt(w) * math.cos(lat)
    assert north_m == pytest.approx(-5.0 * 10.0, rel=0.01)
    assert east_m == pytest.approx(18.0 * 10.0, rel=0.01)
    assert end.alt_msl_m == pytest.approx(start.alt_msl_m, abs=0.3)
