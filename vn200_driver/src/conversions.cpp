#include "conversions.h"

#include "geo_wgs84.h"

#include <cmath>

namespace vn200 {

Quat quat_multiply(const Quat& a, const Quat& b) {
  return {a[3] * b[0] + a[0] * b[3] + a[1] * b[2] - a[2] * b[1],
          a[3] * b[1] - a[0] * b[2] + a[1] * b[3] + a[2] * b[0],
          a[3] * b[2] + a[0] * b[1] - a[1] * b[0] + a[2] * b[3],
          a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2]};
}

Quat quat_conjugate(const Quat& q) { return {-q[0], -q[1], -q[2], q[3]}; }

Vec3 quat_rotate(const Quat& q, const Vec3& v) {
  const Quat p{v[0], v[1], v[2], 0.0};
  const Quat qc{-q[0], -q[1], -q[2], q[3]};
  const Quat r = quat_multiply(quat_multiply(q, p), qc);
  return {r[0], r[1], r[2]};
}

Quat quat_from_ypr_ned(double yaw_rad, double pitch_rad, double roll_rad) {
  const double cy = std::cos(yaw_rad / 2), sy = std::sin(yaw_rad / 2);
  const double cp = std::cos(pitch_rad / 2), sp = std::sin(pitch_rad / 2);
  const double cr = std::cos(roll_rad / 2), sr = std::sin(roll_rad / 2);
  return {sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy, cr * cp * sy - sr * sp * cy,
          cr * cp * cy + sr * sp * sy};
}

Quat ned_frd_to_enu_flu(const Quat& q_ned_frd) {
  const double h = std::sqrt(0.5);
  // ENU<-NED swaps north/east and flips down: a half turn about the (1,1,0)/sqrt2 axis.
  const Quat q_enu_ned{h, h, 0.0, 0.0};
  // FRD<-FLU: a half turn about x.
  const Quat q_frd_flu{1.0, 0.0, 0.0, 0.0};
  return canonical(quat_multiply(quat_multiply(q_enu_ned, q_ned_frd), q_frd_flu));
}

Quat frd_rotation_to_flu(const Quat& q_frd) { return {q_frd[0], -q_frd[1], -q_frd[2], q_frd[3]}; }

Quat canonical(const Quat& q) {
  if (q[3] >= 0) return q;
  return {-q[0], -q[1], -q[2], -q[3]};
}

Vec3 frd_to_flu(const Vec3& v) { return {v[0], -v[1], -v[2]}; }

Vec3 ned_to_enu(const Vec3& v) { return {v[1], v[0], -v[2]}; }

bool is_valid_home(double lat_deg, double lon_deg, double alt_m) {
  GeoRef ref{};
  return geo_ref_init(&ref, lat_deg, lon_deg, alt_m) != 0;
}

Vec3 lla_to_local_enu(double lat_deg, double lon_deg, double alt_m, double ref_lat_deg,
                      double ref_lon_deg, double ref_alt_m) {
  // The stack's one flat earth (geo_wgs84.h), so the tf puts the aircraft where the HA, the
  // controller and the ground station do.
  GeoRef ref{};
  if (!geo_ref_init(&ref, ref_lat_deg, ref_lon_deg, ref_alt_m)) {
    const double nan = std::nan("");
    return {nan, nan, nan};
  }
  double neu[3];
  geo_to_neu_m(&ref, lat_deg, lon_deg, alt_m, neu);
  return {neu[1], neu[0], neu[2]};
}

}  // namespace vn200
