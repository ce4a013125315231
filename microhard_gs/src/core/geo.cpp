#include "geo.h"

#include <cmath>

namespace microhard_gs {
namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kWgs84A_m = 6378137.0;
constexpr double kWgs84E2 = 6.69437999014e-3;  // first eccentricity squared

struct Radii {
  double meridian_m;
  double prime_vertical_m;
};

Radii radii_at(double lat_deg) {
  const double s = std::sin(lat_deg * kPi / 180.0);
  const double w2 = 1.0 - kWgs84E2 * s * s;
  const double w = std::sqrt(w2);
  return Radii{kWgs84A_m * (1.0 - kWgs84E2) / (w2 * w), kWgs84A_m / w};
}
}  // namespace

NorthEastFt geodetic_to_north_east_ft(const GeoPoint& home, double lat_deg, double lon_deg) {
  const Radii r = radii_at(home.lat_deg);
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
  const Radii r = radii_at(home.lat_deg);
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
