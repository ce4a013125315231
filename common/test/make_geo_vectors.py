#!/usr/bin/env python3
"""Writes geo_vectors.csv, the geodesy vectors the C (arduino_ha/test/test_geo_wgs84.cpp) and the
Python (common/test/test_stack_common.py) sides of the stack both check: a point's north, east
and up [ft] from a reference point (home) by the stack's flat earth (geo_wgs84.h's comment), here
computed afresh in Python from the WGS84 constants, so the file is a second implementation the C
is held to, not the C's output copied back. The rows cover the antimeridian both ways (and a home
on it), the equator, both hemispheres, high latitude and next to a pole.

usage: make_geo_vectors.py > geo_vectors.csv"""
import math
import sys

A_M, E2 = 6378137.0, 6.69437999014e-3  # WGS84 (NIMA TR8350.2)
FT_PER_M = 1.0 / 0.3048                   # the international foot

# name: (home lat, lon, alt m), (point lat, lon, alt m)
ROWS = [
    ("kansas_3000ft_north_east", (38.9717, -95.2353, 250.0), (38.9780, -95.2270, 330.0)),
    ("at_home", (38.9717, -95.2353, 250.0), (38.9717, -95.2353, 250.0)),
    ("equator_origin", (0.0, 0.0, 0.0), (0.01, 0.01, 10.0)),
    ("sixty_north_south_west", (60.0, 10.0, 100.0), (59.99, 9.98, 80.0)),
    ("sydney_south_east", (-33.9, 151.2, 20.0), (-33.91, 151.21, 60.0)),
    ("antimeridian_home_west_point_east", (-16.78, 179.9998, 5.0), (-16.7799, -179.9998, 50.0)),
    ("antimeridian_home_east_point_west", (-16.78, -179.9998, 5.0), (-16.7801, 179.9998, 50.0)),
    ("home_on_180_point_east", (-16.78, 180.0, 0.0), (-16.78, -179.999, 0.0)),
    ("home_on_minus_180_point_west", (-16.78, -180.0, 0.0), (-16.78, 179.999, 0.0)),
    ("next_to_the_north_pole", (89.9, 45.0, 0.0), (89.901, 46.0, 30.0)),
    ("far_from_180_same_offset", (-16.78, 0.0002, 5.0), (-16.7799, 0.0006, 50.0)),
]


def neu_ft(home, point):
    lat0 = math.radians(home[0])
    w2 = 1.0 - E2 * math.sin(lat0) ** 2
    meridian_m = A_M * (1.0 - E2) / (w2 * math.sqrt(w2))
    prime_vertical_m = A_M / math.sqrt(w2)
    dlon = point[1] - home[1]
    dlon = dlon - 360.0 if dlon > 180.0 else dlon + 360.0 if dlon < -180.0 else dlon
    north = math.radians(point[0] - home[0]) * meridian_m
    east = math.radians(dlon) * prime_vertical_m * math.cos(lat0)
    return north * FT_PER_M, east * FT_PER_M, (point[2] - home[2]) * FT_PER_M


def main():
    out = sys.stdout
    out.write("# written by make_geo_vectors.py; name,home_lat_deg,home_lon_deg,home_alt_m,lat_deg,lon_deg,"
              "alt_m,north_ft,east_ft,up_ft\n")
    for name, home, point in ROWS:
        n, e, u = neu_ft(home, point)
        out.write("%s,%r,%r,%r,%r,%r,%r,%.9f,%.9f,%.9f\n" % ((name,) + home + point + (n, e, u)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
