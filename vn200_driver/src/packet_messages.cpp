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

MountFlu mount_flu(const SensorMount& m) {
  MountFlu out;
  out.t_m = frd_to_flu({m.x_m, m.y_m, m.z_m});
  out.q_base_sensor = canonical(frd_rotation_to_flu(
      quat_from_ypr_ned(m.yaw_deg * kDegToRad, m.pitch_deg * kDegToRad, m.roll_deg * kDegToRad)));
  return out;
}

BasePose base_pose(const VnBinaryData& d, const MountFlu& mount, double ref_lat_deg,
                   double ref_lon_deg, double ref_alt_m) {
  const Quat q_enu_sensor = ned_frd_to_enu_flu(attitude_ned(d));
  BasePose pose;
  pose.q_enu_base = canonical(quat_multiply(q_enu_sensor, quat_conjugate(mount.q_base_sensor)));
  const Vec3 sensor =
      lla_to_local_enu(d.lat_deg, d.lon_deg, d.alt_m, ref_lat_deg, ref_lon_deg, ref_alt_m);
  const Vec3 arm = quat_rotate(pose.q_enu_base, mount.t_m);
  pose.p_enu_m = {sensor[0] - arm[0], sensor[1] - arm[1], sensor[2] - arm[2]};
  return pose;
}

geometry_msgs::TransformStamped to_transform(const ros::Time& stamp, const std::string& parent,
                                             const std::string& child, const Vec3& t_m,
                                             const Quat& q) {
  geometry_msgs::TransformStamped tf;
  tf.header = header(stamp, parent);
  tf.child_frame_id = child;
  set_vec(&tf.transform.translation, t_m);
  set_quat(&tf.transform.rotation, q);
  return tf;
}

geometry_msgs::TransformStamped to_mount_transform(const MountFlu& mount, const ros::Time& stamp,
                                                   const std::string& base_frame_id,
                                                   const std::string& frame_id) {
  return to_transform(stamp, base_frame_id, frame_id, mount.t_m, mount.q_base_sensor);
}

geometry_msgs::TransformStamped to_frd_transform(const ros::Time& stamp,
                                                 const std::string& frame_id,
                                                 const std::string& frd_frame_id) {
  return to_transform(stamp, frame_id, frd_frame_id, {0.0, 0.0, 0.0}, {1.0, 0.0, 0.0, 0.0});
}

double gyro_rate_variance(double rate_hz) {
  constexpr double kGyroNoiseDensityRadpsPerRtHz = 0.0035 * kDegToRad;
  return kGyroNoiseDensityRadpsPerRtHz * kGyroNoiseDensityRadpsPerRtHz * rate_hz / 2.0;
}

nav_msgs::Odometry to_odometry(const VnBinaryData& d, const BasePose& pose, const MountFlu& mount,
                               const ros::Time& stamp, const std::string& odom_frame_id,
                               const std::string& base_frame_id, double angular_rate_var) {
  nav_msgs::Odometry odom;
  odom.header = header(stamp, odom_frame_id);
  odom.child_frame_id = base_frame_id;
  odom.pose.pose.position.x = pose.p_enu_m[0];
  odom.pose.pose.position.y = pose.p_enu_m[1];
  odom.pose.pose.position.z = pose.p_enu_m[2];
  set_quat(&odom.pose.pose.orientation, pose.q_enu_base);
  // The sensor moves with base_link plus the lever arm's swing: v_sensor = v_base + w x r.
  const Vec3 w_base = quat_rotate(mount.q_base_sensor, frd_to_flu(vec3(d.angular_rate_radps)));
  const Vec3 v_sensor_base =
      quat_rotate(quat_conjugate(pose.q_enu_base), ned_to_enu(vec3(d.vel_ned_mps)));
  const Vec3& r = mount.t_m;
  const Vec3 swing{w_base[1] * r[2] - w_base[2] * r[1], w_base[2] * r[0] - w_base[0] * r[2],
                   w_base[0] * r[1] - w_base[1] * r[0]};
  set_vec(&odom.twist.twist.linear,
          {v_sensor_base[0] - swing[0], v_sensor_base[1] - swing[1], v_sensor_base[2] - swing[2]});
  set_vec(&odom.twist.twist.angular, w_base);
  // Row-major 6x6 (x, y, z, rotation about x, y, z): the diagonals at 0, 7, 14, 21, 28, 35.
  if (d.has & VN_HAS_INS_POS_UNC) {
    const double var = static_cast<double>(d.ins_pos_unc_m) * d.ins_pos_unc_m;
    odom.pose.covariance[0] = odom.pose.covariance[7] = odom.pose.covariance[14] = var;
  }
  if (d.has & VN_HAS_YPR_UNC) {
    const double yaw = d.ypr_unc_deg[0] * kDegToRad, pitch = d.ypr_unc_deg[1] * kDegToRad,
                 roll = d.ypr_unc_deg[2] * kDegToRad;
    odom.pose.covariance[21] = roll * roll;
    odom.pose.covariance[28] = pitch * pitch;
    odom.pose.covariance[35] = yaw * yaw;
  }
  if (d.has & VN_HAS_INS_VEL_UNC) {
    // One figure for every direction, so it holds in body axes as it does in NED.
    const double var = static_cast<double>(d.ins_vel_unc_mps) * d.ins_vel_unc_mps;
    odom.twist.covariance[0] = odom.twist.covariance[7] = odom.twist.covariance[14] = var;
  }
  if (d.has & VN_HAS_ANGULAR_RATE) {
    odom.twist.covariance[21] = odom.twist.covariance[28] = odom.twist.covariance[35] =
        angular_rate_var;
  }
  return odom;
}

}  // namespace vn200
