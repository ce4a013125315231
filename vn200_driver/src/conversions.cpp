#include "conversions.h"

#include <drone_ros_common/wgs84.h>

#include <cmath>

namespace vn200 {

Quat quatMultiply(const Quat& a, const Quat& b) {
  return {a[3] * b[0] + a[0] * b[3] + a[1] * b[2] - a[2] * b[1],
          a[3] * b[1] - a[0] * b[2] + a[1] * b[3] + a[2] * b[0],
          a[3] * b[2] + a[0] * b[1] - a[1] * b[0] + a[2] * b[3],
          a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2]};
}

Vec3 quatRotate(const Quat& q, const Vec3& v) {
  const Quat p{v[0], v[1], v[2], 0.0};
  const Quat qc{-q[0], -q[1], -q[2], q[3]};
  const Quat r = quatMultiply(quatMultiply(q, p), qc);
  return {r[0], r[1], r[2]};
}

Quat quatFromYprNed(double yaw_rad, double pitch_rad, double roll_rad) {
  const double cy = std::cos(yaw_rad / 2), sy = std::sin(yaw_rad / 2);
  const double cp = std::cos(pitch_rad / 2), sp = std::sin(pitch_rad / 2);
  const double cr = std::cos(roll_rad / 2), sr = std::sin(roll_rad / 2);
  return {sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy, cr * cp * sy - sr * sp * cy,
          cr * cp * cy + sr * sp * sy};
}

Quat nedFrdToEnuFlu(const Quat& q_ned_frd) {
  const double h = std::sqrt(0.5);
  // ENU<-NED swaps north/east and flips down: a half turn about the (1,1,0)/sqrt2 axis.
  const Quat q_enu_ned{h, h, 0.0, 0.0};
  // FRD<-FLU: a half turn about x.
  const Quat q_frd_flu{1.0, 0.0, 0.0, 0.0};
  Quat q = quatMultiply(quatMultiply(q_enu_ned, q_ned_frd), q_frd_flu);
  if (q[3] < 0) {
    for (double& c : q) c = -c;  // one canonical sign keeps consumers' diffs smooth
  }
  return q;
}

Vec3 frdToFlu(const Vec3& v) { return {v[0], -v[1], -v[2]}; }

Vec3 nedToEnu(const Vec3& v) { return {v[1], v[0], -v[2]}; }

Vec3 llaToLocalEnu(double lat_deg, double lon_deg, double alt_m, double ref_lat_deg,
                   double ref_lon_deg, double ref_alt_m) {
  // The same flat earth the HA, the controller and the ground station use, so the tf puts the
  // aircraft where they do.
  const drone_ros_common::Wgs84Radii r = drone_ros_common::wgs84_radii_at(ref_lat_deg);
  const double north = (lat_deg - ref_lat_deg) * kDegToRad * r.meridian_m;
  const double east =
      (lon_deg - ref_lon_deg) * kDegToRad * r.prime_vertical_m * std::cos(ref_lat_deg * kDegToRad);
  return {east, north, alt_m - ref_alt_m};
}

}  // namespace vn200
