"""The Python side's two flat-earth conversions (the verdicts' and the report's) take longitude the
short way round, as geo_wgs84.c does: an aircraft that crosses the antimeridian near home (Fiji,
Taveuni at 180 deg) is feet from it, not the Earth's circumference. Judged against the exact local
east/north of the WGS84 ellipsoid (ECEF to ENU), an independent method."""
import math

import pytest

from stack_common import geo
from report_core.flight_log import ned_from_home

A_M, E2, FT_PER_M = 6378137.0, 6.69437999014e-3, 1.0 / 0.3048


def ecef_m(lat_deg, lon_deg):
    lat, lon = math.radians(lat_deg), math.radians(lon_deg)
    n = A_M / math.sqrt(1.0 - E2 * math.sin(lat) ** 2)
    return (n * math.cos(lat) * math.cos(lon), n * math.cos(lat) * math.sin(lon),
            n * (1.0 - E2) * math.sin(lat))


def exact_north_east_ft(home, lat_deg, lon_deg):
    """East and north of the tangent plane at home, on the ellipsoid (height 0)."""
    h, p = ecef_m(*home), ecef_m(lat_deg, lon_deg)
    d = [p[i] - h[i] for i in range(3)]
    lat, lon = math.radians(home[0]), math.radians(home[1])
    east = -math.sin(lon) * d[0] + math.cos(lon) * d[1]
    north = (-math.sin(lat) * math.cos(lon) * d[0] - math.sin(lat) * math.sin(lon) * d[1] +
             math.cos(lat) * d[2])
    return north * FT_PER_M, east * FT_PER_M


# (home, point): 0.0004 deg of longitude (about 140 ft) across the antimeridian, both ways, and
# the same offset away from it, which must give the same answer.
CASES = {
    "home_west_of_180_point_east": ((-16.78, 179.9998), (-16.7799, -179.9998)),
    "home_east_of_180_point_west": ((-16.78, -179.9998), (-16.7801, 179.9998)),
    "far_from_180": ((-16.78, 0.0002), (-16.7799, 0.0006)),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_a_point_across_the_antimeridian_is_where_it_is_in_the_verdicts_and_the_report(case):
    home, (lat, lon) = CASES[case]
    north_ft, east_ft = exact_north_east_ft(home, lat, lon)
    assert abs(east_ft) == pytest.approx(140.0, abs=5.0)  # the case is what it says
    v_north, v_east = geo.north_east_ft(home, lat, lon)  # what the verdicts call
    r_north, r_east = ned_from_home([lat], [lon], home[0], home[1])
    for n, e in ((v_north, v_east), (float(r_north[0]), float(r_east[0]))):
        assert n == pytest.approx(north_ft, abs=0.01)
        assert e == pytest.approx(east_ft, abs=0.01)
