// The WGS84 radii of curvature at a latitude: the flat earth around home that the HP side uses
// (ground station, VN-200 tf, the controller's test model) to put a latitude/longitude at a
// north/east, the same one the HA core (arduino_ha/src/core/ha_ins.c, C99, its own copy) uses.
// Exact at the reference latitude, off by well under a foot within a mission's radius.
#ifndef DRONE_ROS_COMMON_WGS84_H
#define DRONE_ROS_COMMON_WGS84_H

#include <cmath>

namespace drone_ros_common {

struct Wgs84Radii {
  double meridian_m;        // north: metres per radian of latitude
  double prime_vertical_m;  // east: times cos(latitude), metres per radian of longitude
};

inline Wgs84Radii wgs84_radii_at(double lat_deg) {
  constexpr double kA_m = 6378137.0;
  constexpr double kE2 = 6.69437999014e-3;  // first eccentricity squared
  const double s = std::sin(lat_deg * 3.14159265358979323846 / 180.0);
  const double w2 = 1.0 - kE2 * s * s;
  const double w = std::sqrt(w2);
  return Wgs84Radii{kA_m * (1.0 - kE2) / (w2 * w), kA_m / w};
}

}  // namespace drone_ros_common

#endif
