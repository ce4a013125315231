#include "geo.h"

#include <cmath>

#include "geo_wgs84.h"

namespace microhard_gs {
namespace {
// The stack's one flat earth (common/src/geo_wgs84.h). A home that geo_ref_init refuses
// is never used: the node only takes a home is_valid_position() accepts.
GeoRef ref_of(const GeoPoint& home) {
  GeoRef r{};
  if (!geo_ref_init(&r, home.lat_deg, home.lon_deg, home.alt_m)) {
    geo_ref_init(&r, home.lat_deg, home.lon_deg, 0.0);  // an absurd height: the plane still holds
  }
  return r;
}
}  // namespace

NorthEastFt geodetic_to_north_east_ft(const GeoPoint& home, double lat_deg, double lon_deg) {
  const GeoRef r = ref_of(home);
  double neu_ft[3];
  geo_to_neu_ft(&r, lat_deg, lon_deg, home.alt_m, neu_ft);
  NorthEastFt ne;
  ne.north_ft = neu_ft[0];
  ne.east_ft = neu_ft[1];
  return ne;
}

void north_east_ft_to_geodetic(const GeoPoint& home, const NorthEastFt& ne, double* lat_deg,
                               double* lon_deg) {
  const GeoRef r = ref_of(home);
  const double neu_ft[3] = {ne.north_ft, ne.east_ft, 0.0};
  double alt_m;
  geo_from_neu_ft(&r, neu_ft, lat_deg, lon_deg, &alt_m);
}

bool is_valid_home(const GeoPoint& home) {
  GeoRef judged;
  return geo_ref_init(&judged, home.lat_deg, home.lon_deg, home.alt_m) != 0;
}

bool is_valid_position(double lat_deg, double lon_deg) {
  return std::isfinite(lat_deg) && std::isfinite(lon_deg) && lat_deg >= -90.0 && lat_deg <= 90.0 &&
         lon_deg >= -180.0 && lon_deg <= 180.0 && !(lat_deg == 0.0 && lon_deg == 0.0);
}

}  // namespace microhard_gs
