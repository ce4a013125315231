// The stack's one latitude/longitude <-> north/east/up conversion (core/geo_wgs84.c), against
// published WGS84 arc lengths and an exact ellipsoid (ECEF -> local east/north) computation.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "geo_wgs84.h"
#include "home_vectors.h"

namespace {

constexpr double kFtPerM = 1.0 / 0.3048;

// Length of one degree of latitude / longitude on WGS84 (the standard table, e.g. the NGA's
// and Wikipedia's "Latitude" article), in metres, at 0, 15, ..., 75 deg.
struct ArcRow {
  double lat_deg, lat_arc_m, lon_arc_m;
};
constexpr ArcRow kPublished[] = {
    {0.0, 110574.0, 111320.0}, {15.0, 110649.0, 107551.0}, {30.0, 110852.0, 96486.0},
    {45.0, 111132.0, 78847.0}, {60.0, 111412.0, 55800.0},  {75.0, 111618.0, 28902.0},
};

struct Ecef {
  long double x, y, z;
};
Ecef ecef(long double lat_deg, long double lon_deg, long double h_m) {
  const long double la = lat_deg * 3.14159265358979323846264L / 180.0L;
  const long double lo = lon_deg * 3.14159265358979323846264L / 180.0L;
  const long double n =
      GEO_WGS84_A_M / std::sqrt(1.0L - GEO_WGS84_E2 * std::sin(la) * std::sin(la));
  return {(n + h_m) * std::cos(la) * std::cos(lo), (n + h_m) * std::cos(la) * std::sin(lo),
          (n * (1.0L - GEO_WGS84_E2) + h_m) * std::sin(la)};
}
// Exact local north/east [m] of a point seen from a reference on the ellipsoid.
void exact_north_east_m(double lat0, double lon0, double lat, double lon, double* n, double* e) {
  const Ecef a = ecef(lat0, lon0, 0.0L), b = ecef(lat, lon, 0.0L);
  const long double dx = b.x - a.x, dy = b.y - a.y, dz = b.z - a.z;
  const long double la = lat0 * 3.14159265358979323846264L / 180.0L;
  const long double lo = lon0 * 3.14159265358979323846264L / 180.0L;
  *e = static_cast<double>(-std::sin(lo) * dx + std::cos(lo) * dy);
  *n = static_cast<double>(-std::sin(la) * std::cos(lo) * dx - std::sin(la) * std::sin(lo) * dy +
                           std::cos(la) * dz);
}

GeoRef ref_at(double lat, double lon, double alt = 0.0) {
  GeoRef r{};
  EXPECT_EQ(geo_ref_init(&r, lat, lon, alt), 1);
  return r;
}

// Worst horizontal error [ft] over every direction at distance_ft from a reference.
double worst_error_ft(double lat0, double distance_ft, bool single_precision) {
  const GeoRef r = ref_at(lat0, -97.5);
  double worst = 0.0;
  for (int az = 0; az < 360; az += 5) {
    const double a = az * M_PI / 180.0;
    const double neu[3] = {distance_ft * std::cos(a), distance_ft * std::sin(a), 0.0};
    double lat, lon, alt;
    geo_from_neu_ft(&r, neu, &lat, &lon, &alt);
    double n_m, e_m;
    exact_north_east_m(lat0, -97.5, lat, lon, &n_m, &e_m);
    double n_ft, e_ft;
    if (single_precision) {
      float nf, ef;
      geo_to_ne_ft_f(&r, lat, lon, &nf, &ef);
      n_ft = nf;
      e_ft = ef;
    } else {
      double out[3];
      geo_to_neu_ft(&r, lat, lon, 0.0, out);
      n_ft = out[0];
      e_ft = out[1];
    }
    worst = std::max(worst, std::hypot(n_ft - n_m * kFtPerM, e_ft - e_m * kFtPerM));
  }
  return worst;
}

}  // namespace

TEST(GeoWgs84, OneDegreeMatchesThePublishedArcLengths) {
  for (const ArcRow& row : kPublished) {
    const GeoRef r = ref_at(row.lat_deg, 10.0);
    double neu[3];
    // Half a degree either side: the arc the table gives, centred on its latitude.
    double south[3];
    geo_to_neu_m(&r, row.lat_deg + 0.5, 10.5, 0.0, neu);
    geo_to_neu_m(&r, row.lat_deg - 0.5, 9.5, 0.0, south);
    EXPECT_NEAR(neu[0] - south[0], row.lat_arc_m, 2.0) << row.lat_deg;
    EXPECT_NEAR(neu[1] - south[1], row.lon_arc_m, 2.0) << row.lat_deg;
  }
}

TEST(GeoWgs84, RadiiAreTheTextbookValuesAtEquatorAndPole) {
  double m, n;
  geo_radii_m(0.0, &m, &n);
  EXPECT_NEAR(m, 6335439.327, 0.01);  // a (1 - e2)
  EXPECT_NEAR(n, 6378137.0, 1e-6);    // a
  geo_radii_m(90.0, &m, &n);
  EXPECT_NEAR(m, 6399593.626, 0.01);  // a / sqrt(1 - e2), both
  EXPECT_NEAR(n, 6399593.626, 0.01);
}

TEST(GeoWgs84, ErrorAt3000FtFromHomeIsAFractionOfAFoot) {
  // Double precision (the HP side) and the single-precision path the Due flies with.
  EXPECT_LT(worst_error_ft(45.0, 3000.0, false), 0.26);
  EXPECT_LT(worst_error_ft(60.0, 3000.0, false), 0.44);
  EXPECT_LT(worst_error_ft(45.0, 3000.0, true), 0.26);
  // The float scaling itself: the Due's figures against the double ones.
  const GeoRef r = ref_at(45.0, -97.5);
  const double neu[3] = {-2121.0, 2121.0, 0.0};
  double lat, lon, alt;
  geo_from_neu_ft(&r, neu, &lat, &lon, &alt);
  float nf, ef;
  geo_to_ne_ft_f(&r, lat, lon, &nf, &ef);
  EXPECT_NEAR(nf, -2121.0, 1e-3);
  EXPECT_NEAR(ef, 2121.0, 1e-3);
}

TEST(GeoWgs84, RoundTripReturnsThePointAndItsHeight) {
  const GeoRef r = ref_at(40.4237, -86.9212, 185.0);
  const double neu_ft[3] = {1234.5, -876.25, 300.0};
  double lat, lon, alt;
  geo_from_neu_ft(&r, neu_ft, &lat, &lon, &alt);
  double back[3];
  geo_to_neu_ft(&r, lat, lon, alt, back);
  EXPECT_NEAR(back[0], 1234.5, 1e-6);
  EXPECT_NEAR(back[1], -876.25, 1e-6);
  EXPECT_NEAR(back[2], 300.0, 1e-6);
  EXPECT_NEAR(alt, 185.0 + 300.0 * 0.3048, 1e-9);
}

TEST(GeoWgs84, HomeIsTheOrigin) {
  const GeoRef r = ref_at(-33.9, 151.2, 20.0);
  double neu[3];
  geo_to_neu_m(&r, -33.9, 151.2, 20.0, neu);
  EXPECT_EQ(neu[0], 0.0);
  EXPECT_EQ(neu[1], 0.0);
  EXPECT_EQ(neu[2], 0.0);
}

TEST(GeoWgs84, AcrossTheAntimeridianTakesTheShortWayRound) {
  const GeoRef r = ref_at(0.0, 179.999);
  double neu[3];
  geo_to_neu_m(&r, 0.0, -179.999, 0.0, neu);
  EXPECT_NEAR(neu[1], 0.002 * 111319.49, 0.01);
  const double west[3] = {0.0, 300.0, 0.0};
  double lat, lon, alt;
  geo_from_neu_m(&r, west, &lat, &lon, &alt);
  EXPECT_LT(lon, -179.99);
  // And from the other side: home just west of the line, a point just east of it.
  const GeoRef w = ref_at(0.0, -179.999);
  geo_to_neu_m(&w, 0.0, 179.999, 0.0, neu);
  EXPECT_NEAR(neu[1], -0.002 * 111319.49, 0.01);
  const double east[3] = {0.0, -300.0, 0.0};
  geo_from_neu_m(&w, east, &lat, &lon, &alt);
  EXPECT_GT(lon, 179.99);
}

// At a pole east has no length: a home there gives every point the home's longitude back, not a
// division by zero.
TEST(GeoWgs84, AtAPoleTheLongitudeStaysTheHomes) {
  const GeoRef r = ref_at(90.0, 12.0);
  const double neu[3] = {-100.0, 50.0, 0.0};
  double lat, lon, alt;
  geo_from_neu_m(&r, neu, &lat, &lon, &alt);
  EXPECT_DOUBLE_EQ(lon, 12.0);
  EXPECT_LT(lat, 90.0);
}

TEST(GeoWgs84, AReferenceOutOfRangeOrNotANumberIsRefusedAndTheOldOneKept) {
  GeoRef r = ref_at(45.0, 7.0, 100.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(geo_ref_init(&r, 90.5, 7.0, 0.0), 0);
  EXPECT_EQ(geo_ref_init(&r, 45.0, -180.5, 0.0), 0);
  EXPECT_EQ(geo_ref_init(&r, nan, 7.0, 0.0), 0);
  EXPECT_EQ(geo_ref_init(&r, 45.0, nan, 0.0), 0);
  EXPECT_EQ(geo_ref_init(&r, 45.0, 7.0, nan), 0);
  EXPECT_EQ(geo_ref_init(&r, 45.0, 7.0, 2.0e5), 0);
  EXPECT_EQ(r.lat_deg, 45.0);
  EXPECT_EQ(r.lon_deg, 7.0);
  EXPECT_EQ(r.alt_m, 100.0);
}

// The judge itself against the table every node that takes /home is tested with
// (test/home_vectors.h): what it refuses leaves the reference as it was.
TEST(GeoWgs84, TheOneJudgeOfAHomeTakesTheTablesHomesAndRefusesTheRest) {
  for (const HomeVector& v : kHomeVectors) {
    GeoRef ref;
    ASSERT_EQ(geo_ref_init(&ref, 1.0, 2.0, 3.0), 1);
    EXPECT_EQ(geo_ref_init(&ref, v.lat_deg, v.lon_deg, v.alt_m), v.valid ? 1 : 0) << v.what;
    if (!v.valid) {
      EXPECT_EQ(ref.lat_deg, 1.0) << v.what;
    }
  }
}

// The vectors the Python side checks too (common/test/geo_vectors.csv, written by a Python
// implementation of the same flat earth): the antimeridian both ways and a home on it, both
// hemispheres, next to a pole. The C must give each row's north, east and up to a micro-foot.
TEST(GeoWgs84, TheSharedVectorsOfBothLanguagesHoldForTheC) {
  std::ifstream in(GEO_VECTORS_CSV);
  ASSERT_TRUE(in.good()) << "cannot read " << GEO_VECTORS_CSV;
  std::string line;
  int rows = 0;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string name, cell;
    std::getline(fields, name, ',');
    std::vector<double> v;
    while (std::getline(fields, cell, ',')) v.push_back(std::stod(cell));
    ASSERT_EQ(v.size(), 9u) << line;
    GeoRef ref;
    ASSERT_EQ(geo_ref_init(&ref, v[0], v[1], v[2]), 1) << name;
    double neu_ft[3];
    geo_to_neu_ft(&ref, v[3], v[4], v[5], neu_ft);
    EXPECT_NEAR(neu_ft[0], v[6], 1e-6) << name;
    EXPECT_NEAR(neu_ft[1], v[7], 1e-6) << name;
    EXPECT_NEAR(neu_ft[2], v[8], 1e-6) << name;
    ++rows;
  }
  EXPECT_GE(rows, 10);
}
