// The homes every node that takes /home must judge alike, since one function judges them all:
// geo_ref_init (common/src/geo_wgs84.h), the HA's own test of the home it latches. The
// controller's sensor board, the vn200 node and the ground station each test their home input
// against this one table (issue 26: "geo_ref_init is the one judge of a valid home").
#pragma once

#include <cmath>
#include <limits>

struct HomeVector {
  const char* what;
  double lat_deg, lon_deg, alt_m;
  bool valid;
};

static const double kHomeNan = std::numeric_limits<double>::quiet_NaN();
static const double kHomeInf = std::numeric_limits<double>::infinity();

static const HomeVector kHomeVectors[] = {
    {"the case study's field", 39.9954, -82.9982, 250.0, true},
    {"the corners of the ranges", -90.0, 180.0, -1.0e4, true},
    {"the other corners", 90.0, -180.0, 1.0e5, true},
    {"lat 0, lon 0: a place, as the HA judges it", 0.0, 0.0, 0.0, true},
    {"beside the antimeridian", -16.5, 179.9999, 12.0, true},
    {"latitude past the pole", 90.0001, 10.0, 0.0, false},
    {"longitude past 180", 10.0, -180.0001, 0.0, false},
    {"altitude above 100 km", 40.0, -83.0, 1.0e5 + 1.0, false},
    {"altitude below -10 km", 40.0, -83.0, -1.0e4 - 1.0, false},
    {"NaN latitude", kHomeNan, -83.0, 250.0, false},
    {"NaN longitude", 40.0, kHomeNan, 250.0, false},
    {"NaN altitude", 40.0, -83.0, kHomeNan, false},
    {"infinite altitude", 40.0, -83.0, kHomeInf, false},
};
