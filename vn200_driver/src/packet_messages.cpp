#include "packet_messages.h"

namespace vn200 {
namespace {

constexpr uint64_t kNsPerWeek = 604800ull * 1000000000ull;

void set_quat(geometry_msgs::Quaternion* m, const Quat& q) {
  m->x = q[0];
  m->y = q[1];
  m->z = q[2];
  m->w = q[3];
}

void set_vec(geometry_msgs::Vector3* m, const Vec3& v) {
  m->x = v[0];
  m->y = v[1];
  m->z = v[2];
}

Vec3 vec3(const float* f) { return {f[0], f[1], f[2]}; }

std_msgs::Header header(const ros::Time& stamp, const std::string& frame_id) {
  std_msgs::Header h;
  h.stamp = stamp;
  h.frame_id = frame_id;
  return h;
}

}  // namespace

Quat attitude_ned(const VnBinaryData& d) {
  if (d.has & VN_HAS_QUATERNION)
    return {d.quat_xyzw[0], d.quat_xyzw[1], d.quat_xyzw[2], d.quat_xyzw[3]};
  return quat_from_ypr_ned(d.ypr_deg[0] * kDegToRad, d.ypr_deg[1] * kDegToRad,
                           d.ypr_deg[2] * kDegToRad);
}

drone_ros::ins to_ins(const VnBinaryData& d, const ros::Time& stamp, const std::string& frame_id) {
  drone_ros::ins ins;
  ins.header = header(stamp, frame_id);
  if (d.has & VN_HAS_GPS_TOW) {
    ins.time = static_cast<double>(d.gps_tow_ns) * 1e-9;
  } else if (d.has & VN_HAS_TIME_GPS) {
    ins.time = static_cast<double>(d.time_gps_ns % kNsPerWeek) * 1e-9;
  }
  if (d.has & VN_HAS_GPS_WEEK) {
    ins.week = d.gps_week;
  } else if (d.has & VN_HAS_TIME_GPS) {
    ins.week = static_cast<uint16_t>(d.time_gps_ns / kNsPerWeek);
  }
  ins.usbstatus = 1;
  ins.ins_status = d.ins_status;
  ins.num_sats = d.num_sats;
  ins.gps_fix = d.gps_fix;
  return ins;
}

geometry_msgs::Point to_attitude(const VnBinaryData& d) {
  geometry_msgs::Point att;
  att.x = d.ypr_deg[2] * kDegToRad;
  att.y = d.ypr_deg[1] * kDegToRad;
  att.z = d.ypr_deg[0] * kDegToRad;
  return att;
}

geometry_msgs::Twist to_gps_velocity(const VnBinaryData& d) {
  geometry_msgs::Twist v;
  set_vec(&v.linear, vec3(d.vel_ned_mps));
  return v;
}

sensor_msgs::Imu to_imu_pqr(const VnBinaryData& d, const ros::Time& stamp,
                            const std::string& frd_frame_id) {
  sensor_msgs::Imu pqr;
  pqr.header = header(stamp, frd_frame_id);
  set_quat(&pqr.orientation, attitude_ned(d));
  set_vec(&pqr.angular_velocity, vec3(d.angular_rate_radps));
  set_vec(&pqr.linear_acceleration, vec3(d.accel_mps2));
  return pqr;
}

sensor_msgs::NavSatFix to_nav_sat_fix(const VnBinaryData& d, const ros::Time& stamp,
                                      const std::string& frame_id) {
  sensor_msgs::NavSatFix fix;
  fix.header = header(stamp, frame_id);
  fix.status.status = d.gps_fix >= 2 ? sensor_msgs::NavSatStatus::STATUS_FIX
                                     : sensor_msgs::NavSatStatus::STATUS_NO_FIX;
  fix.status.service = sensor_msgs::NavSatStatus::SERVICE_GPS;
  fix.latitude = d.lat_deg;
  fix.longitude = d.lon_deg;
  fix.altitude = d.alt_m;
  if (d.has & VN_HAS_INS_POS_UNC) {
    const double var = static_cast<double>(d.ins_pos_unc_m) * d.ins_pos_unc_m;
    fix.position_covariance = {var, 0, 0, 0, var, 0, 0, 0, var};
    fix.position_covariance_type = sensor_msgs::NavSatFix::COVARIANCE_TYPE_APPROXIMATED;
  } else if (d.has & VN_HAS_GPS_POS_UNC) {
    const Vec3 u = ned_to_enu(vec3(d.gps_pos_unc_ned_m));
    fix.position_covariance = {u[0] * u[0], 0, 0, 0, u[1] * u[1], 0, 0, 0, u[2] * u[2]};
    fix.position_covariance_type = sensor_msgs::NavSatFix::COVARIANCE_TYPE_DIAGONAL_KNOWN;
  }
  return fix;
}

geometry_msgs::TwistStamped to_velocity_enu(const VnBinaryData& d, const ros::Time& stamp,
                                            const std::string& world_frame_id) {
  geometry_msgs::TwistStamped ve;
  ve.header = header(stamp, world_frame_id);
  set_vec(&ve.twist.linear, ned_to_enu(vec3(d.vel_ned_mps)));
  return ve;
}

sensor_msgs::Imu to_imu(const VnBinaryData& d, const ros::Time& stamp,
                        const std::string& frame_id) {
  sensor_msgs::Imu imu;
  imu.header = header(stamp, frame_id);
  set_quat(&imu.orientation, ned_frd_to_enu_flu(attitude_ned(d)));
  if (d.has & VN_HAS_YPR_UNC) {
    const double r = d.ypr_unc_deg[2] * kDegToRad, p = d.ypr_unc_deg[1] * kDegToRad,
                 y = d.ypr_unc_deg[0] * kDegToRad;
    imu.orientation_covariance = {r * r, 0, 0, 0, p * p, 0, 0, 0, y * y};
  }
  set_vec(&imu.angular_velocity, frd_to_flu(vec3(d.angular_rate_radps)));
  set_vec(&imu.linear_acceleration, frd_to_flu(vec3(d.accel_mps2)));
  return imu;
}

sensor_msgs::MagneticField to_magnetic_field(const VnBinaryData& d,
                                             const std_msgs::Header& header) {
  sensor_msgs::MagneticField mag;
  mag.header = header;
  const Vec3 m = frd_to_flu(vec3(d.mag_gauss));
  set_vec(&mag.magnetic_field, {m[0] * kGaussToTesla, m[1] * kGaussToTesla, m[2] * kGaussToTesla});
  return mag;
}

sensor_msgs::FluidPressure to_fluid_pressure(const VnBinaryData& d,
                                             const std_msgs::Header& header) {
  sensor_msgs::FluidPressure pr;
  pr.header = header;
  pr.fluid_pressure = d.pressure_kpa * kKpaToPa;
  return pr;
}

sensor_msgs::Temperature to_temperature(const VnBinaryData& d, const std_msgs::Header& header) {
  sensor_msgs::Temperature t;
  t.header = header;
  t.temperature = d.temp_c;
  return t;
}

geometry_msgs::TransformStamped to_transform(const VnBinaryData& d, const ros::Time& stamp,
                                             const std::string& world_frame_id,
                                             const std::string& frame_id, double ref_lat_deg,
                                             double ref_lon_deg, double ref_alt_m) {
  geometry_msgs::TransformStamped tf;
  tf.header = header(stamp, world_frame_id);
  tf.child_frame_id = frame_id;
  const Vec3 p =
      lla_to_local_enu(d.lat_deg, d.lon_deg, d.alt_m, ref_lat_deg, ref_lon_deg, ref_alt_m);
  tf.transform.translation.x = p[0];
  tf.transform.translation.y = p[1];
  tf.transform.translation.z = p[2];
  set_quat(&tf.transform.rotation, ned_frd_to_enu_flu(attitude_ned(d)));
  return tf;
}

}  // namespace vn200
