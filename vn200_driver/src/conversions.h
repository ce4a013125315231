// Frame conversions from the VN-200's conventions (attitude of the body x-forward/y-right/z-down
// frame relative to local NED) to ROS REP-103 (body x-forward/y-left/z-up, world ENU).
#pragma once

#include <array>

namespace vn200 {

using Vec3 = std::array<double, 3>;
using Quat = std::array<double, 4>;  // x, y, z, w

constexpr double kDegToRad = 0.017453292519943295;
constexpr double kGaussToTesla = 1e-4;
constexpr double kKpaToPa = 1000.0;

Quat quat_multiply(const Quat& a, const Quat& b);
Quat quat_conjugate(const Quat& q);
// Rotates v by unit quaternion q.
Vec3 quat_rotate(const Quat& q, const Vec3& v);
// Body(FRD)->NED quaternion from yaw, pitch, roll [rad] (aerospace 3-2-1 sequence).
Quat quat_from_ypr_ned(double yaw_rad, double pitch_rad, double roll_rad);
// Body(FRD)->NED attitude to body(FLU)->ENU attitude.
Quat ned_frd_to_enu_flu(const Quat& q_ned_frd);
// A rotation between two FRD frames as the same rotation between their FLU twins (a half turn
// about x on both sides), e.g. a sensor's mount measured in the airframe's FRD axes.
Quat frd_rotation_to_flu(const Quat& q_frd);
// w >= 0: q and -q are one rotation; one sign keeps consumers' differences smooth.
Quat canonical(const Quat& q);
Vec3 frd_to_flu(const Vec3& v);
Vec3 ned_to_enu(const Vec3& v);
// East/north/up offset [m] of (lat, lon, alt) from a reference, on a local tangent plane
// (adequate over the few kilometres of a research flight).
Vec3 lla_to_local_enu(double lat_deg, double lon_deg, double alt_m, double ref_lat_deg,
                      double ref_lon_deg, double ref_alt_m);
// A home the stack can take (/home): the HA's own test, geo_ref_init, so the odometry's origin is
// never one the flat earth refuses (which would make every offset NaN).
bool is_valid_home(double lat_deg, double lon_deg, double alt_m);

}  // namespace vn200
