"""The seeded turbulence has the Dryden low-altitude intensities and autocorrelations."""
import math
import os
import statistics

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
from hil.fdm.turbulence import Turbulence  # noqa: E402

FT = 0.3048
KT = 0.514444
DT = 0.01
HEIGHT_M = 60.0
AIRSPEED = 18.0


def gusts(level, seed, seconds, heading_rad=0.0):
    t = Turbulence(level, seed, DT)
    return [t.step(HEIGHT_M, AIRSPEED, heading_rad) for _ in range(int(seconds / DT))]


def autocorrelation(x, lag):
    m = statistics.fmean(x)
    num = sum((a - m) * (b - m) for a, b in zip(x, x[lag:]))
    return num / sum((a - m) ** 2 for a in x)


def dryden_low_altitude(w20_kt):
    """MIL-F-8785C below 1000 ft: sigma_w = 0.1 W20, sigma_u = sigma_w / (0.177 + 0.000823 h)^0.4,
    L_w = h, L_u = h / (0.177 + 0.000823 h)^1.2, h in ft."""
    h = HEIGHT_M / FT
    d = 0.177 + 0.000823 * h
    sigma_w = 0.1 * w20_kt * KT
    return sigma_w / d ** 0.4, sigma_w, h / d ** 1.2 * FT, h * FT


@pytest.fixture(scope="module")
def moderate():
    return gusts("moderate", 11, 3000.0)


def test_moderate_turbulence_has_the_dryden_intensities(moderate):
    sigma_u, sigma_w, _, _ = dryden_low_altitude(30.0)
    north, east, down = zip(*moderate)        # heading north: u is north, v is east
    assert statistics.pstdev(north) == pytest.approx(sigma_u, rel=0.15)
    assert statistics.pstdev(east) == pytest.approx(sigma_u, rel=0.15)
    assert statistics.pstdev(down) == pytest.approx(sigma_w, rel=0.1)
    assert abs(statistics.fmean(down)) < 0.1 * sigma_w


def test_gusts_stay_correlated_as_the_dryden_autocorrelations_say(moderate):
    """Dryden: R_u(xi) = exp(-xi / L_u); R_v, R_w(xi) = exp(-xi / L) (1 - xi / (2 L)), xi = V t."""
    _, _, l_u, l_w = dryden_low_altitude(30.0)
    north, east, down = zip(*moderate)
    for lag_s in (1.0, 3.0):
        lag = int(lag_s / DT)
        xi = AIRSPEED * lag_s
        assert autocorrelation(north, lag) == pytest.approx(math.exp(-xi / l_u), abs=0.06)
        lateral = math.exp(-xi / l_u) * (1 - xi / (2 * l_u))
        vertical = math.exp(-xi / l_w) * (1 - xi / (2 * l_w))
        assert autocorrelation(east, lag) == pytest.approx(lateral, abs=0.06)
        assert autocorrelation(down, lag) == pytest.approx(vertical, abs=0.06)


def test_moderate_is_light_doubled_and_none_is_calm():
    light = gusts("light", 5, 20.0)
    moderate = gusts("moderate", 5, 20.0)
    for a, b in zip(light, moderate):
        assert b == pytest.approx(tuple(2.0 * x for x in a), rel=1e-12)
    assert set(gusts("none", 5, 1.0)) == {(0.0, 0.0, 0.0)}


def test_gusts_are_generated_along_the_heading():
    north_heading = gusts("light", 3, 5.0, 0.0)
    east_heading = gusts("light", 3, 5.0, math.pi / 2)
    for (n0, e0, d0), (n1, e1, d1) in zip(north_heading, east_heading):
        # Heading east, the longitudinal gust points east and the lateral one south.
        assert e1 == pytest.approx(n0, abs=1e-12)
        assert n1 == pytest.approx(-e0, abs=1e-12)
        assert d1 == d0
