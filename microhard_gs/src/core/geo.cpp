#include "geo.h"

#include <drone_ros_common/wgs84.h>

#include <cmath>

namespace microhard_gs {
namespace {
constexpr double kPi = 3.14159265358979323846;
using drone_ros_common::wgs84_radii_at;
}  // namespace

NorthEastFt geodetic_to_north_east_ft(const GeoPoint& home, double lat_deg, double lon_deg) {
  const drone_ros_common::Wgs84Radii r = wgs84_radii_at(home.lat_deg);
  double dlon_deg = lon_deg - home.lon_deg;
  // Take the short way round across the antimeridian.
  if (dlon_deg > 180.0) dlon_deg -= 360.0;
  if (dlon_deg < -180.0) dlon_deg += 360.0;
  NorthEastFt ne;
  ne.north_ft = (lat_deg - home.lat_deg) * kPi / 180.0 * r.meridian_m * kFeetPerMetre;
  ne.east_ft = dlon_deg * kPi / 180.0 * r.prime_vertical_m * std::cos(home.lat_deg * kPi / 180.0) *
               kFeetPerMetre;
  return ne;
}

void north_east_ft_to_geodetic(const GeoPoint& home, const NorthEastFt& ne, double* lat_deg,
                               double* lon_deg) {
  const drone_ros_common::Wgs84Radii r = wgs84_radii_at(home.lat_deg);
  *lat_deg = home.lat_deg + ne.north_ft / kFeetPerMetre / r.meridian_m * 180.0 / kPi;
  *lon_deg = home.lon_deg + ne.east_ft / kFeetPerMetre /
                                (r.prime_vertical_m * std::cos(home.lat_deg * kPi / 180.0)) *
                                180.0 / kPi;
}

bool is_valid_position(double lat_deg, double lon_deg) {
  return std::isfinite(lat_deg) && std::isfinite(lon_deg) && lat_deg >= -90.0 && lat_deg <= 90.0 &&
         lon_deg >= -180.0 && lon_deg <= 180.0 && !(lat_deg == 0.0 && lon_deg == 0.0);
}

}  // namespace microhard_gs
