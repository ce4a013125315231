// What the node publishes for a packet: each converter on its own, no ROS master.
#include <gtest/gtest.h>

#include <cmath>

#include "packet_messages.h"

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr uint64_t kNsPerWeek = 604800ull * 1000000000ull;

VnBinaryData packet() {
  VnBinaryData d{};
  d.ypr_deg[0] = 90.0f;   // heading east
  d.ypr_deg[1] = 5.0f;    // nose up
  d.ypr_deg[2] = -10.0f;  // left wing down
  d.lat_deg = 40.11;
  d.lon_deg = -88.22;
  d.alt_m = 220.0;
  d.vel_ned_mps[0] = 3.0f;
  d.vel_ned_mps[1] = 20.0f;
  d.vel_ned_mps[2] = -1.0f;
  d.angular_rate_radps[0] = 0.1f;
  d.angular_rate_radps[1] = 0.2f;
  d.angular_rate_radps[2] = 0.3f;
  d.has = VN_HAS_YPR | VN_HAS_POSITION_LLA | VN_HAS_VEL_NED | VN_HAS_ANGULAR_RATE;
  return d;
}

TEST(PacketMessages, InsCarriesGpsTimeOfWeekAndWeekFromTheGpsGroup) {
  VnBinaryData d = packet();
  d.has |= VN_HAS_GPS_TOW | VN_HAS_GPS_WEEK;
  d.gps_tow_ns = 123456789000000ull;
  d.gps_week = 2345;
  d.num_sats = 11;
  d.gps_fix = 3;
  const drone_ros::ins ins = vn200::to_ins(d, ros::Time(5, 0), "vn200");
  EXPECT_DOUBLE_EQ(ins.time, 123456.789);
  EXPECT_EQ(ins.week, 2345);
  EXPECT_EQ(ins.num_sats, 11);
  EXPECT_EQ(ins.gps_fix, 3);
  EXPECT_EQ(ins.usbstatus, 1);
  EXPECT_EQ(ins.header.frame_id, "vn200");
  EXPECT_EQ(ins.header.stamp, ros::Time(5, 0));
}

TEST(PacketMessages, InsFallsBackToGpsTimeSplitIntoWeekAndTimeOfWeek) {
  VnBinaryData d = packet();
  d.has |= VN_HAS_TIME_GPS;
  d.time_gps_ns = 2000 * kNsPerWeek + 7000000000ull;
  const drone_ros::ins ins = vn200::to_ins(d, ros::Time(1, 0), "vn200");
  EXPECT_EQ(ins.week, 2000);
  EXPECT_DOUBLE_EQ(ins.time, 7.0);
}

TEST(PacketMessages, AttitudeIsRollPitchYawInRadiansAsTheThesisControllerReadsIt) {
  const geometry_msgs::Point att = vn200::to_attitude(packet());
  EXPECT_NEAR(att.x, -10.0 * kPi / 180.0, 1e-6);
  EXPECT_NEAR(att.y, 5.0 * kPi / 180.0, 1e-6);
  EXPECT_NEAR(att.z, 90.0 * kPi / 180.0, 1e-6);
}

TEST(PacketMessages, GpsVelocityStaysNedWhileTheRep103VelocityIsEnu) {
  const VnBinaryData d = packet();
  const geometry_msgs::Twist ned = vn200::to_gps_velocity(d);
  EXPECT_FLOAT_EQ(ned.linear.x, 3.0);
  EXPECT_FLOAT_EQ(ned.linear.y, 20.0);
  EXPECT_FLOAT_EQ(ned.linear.z, -1.0);
  const geometry_msgs::TwistStamped enu = vn200::to_velocity_enu(d, ros::Time(1, 0), "map");
  EXPECT_FLOAT_EQ(enu.twist.linear.x, 20.0);  // east
  EXPECT_FLOAT_EQ(enu.twist.linear.y, 3.0);   // north
  EXPECT_FLOAT_EQ(enu.twist.linear.z, 1.0);   // up
  EXPECT_EQ(enu.header.frame_id, "map");
}

TEST(PacketMessages, FixUsesTheInsUncertaintyBeforeTheGpsOne) {
  VnBinaryData d = packet();
  d.gps_fix = 3;
  d.ins_pos_unc_m = 2.0f;
  d.gps_pos_unc_ned_m[0] = 5.0f;
  d.has |= VN_HAS_INS_POS_UNC | VN_HAS_GPS_POS_UNC;
  sensor_msgs::NavSatFix fix = vn200::to_nav_sat_fix(d, ros::Time(1, 0), "vn200");
  EXPECT_EQ(fix.status.status, sensor_msgs::NavSatStatus::STATUS_FIX);
  EXPECT_DOUBLE_EQ(fix.latitude, 40.11);
  EXPECT_DOUBLE_EQ(fix.position_covariance[0], 4.0);
  EXPECT_EQ(fix.position_covariance_type, sensor_msgs::NavSatFix::COVARIANCE_TYPE_APPROXIMATED);
  d.has &= ~static_cast<uint32_t>(VN_HAS_INS_POS_UNC);
  d.gps_fix = 1;
  fix = vn200::to_nav_sat_fix(d, ros::Time(1, 0), "vn200");
  EXPECT_EQ(fix.status.status, sensor_msgs::NavSatStatus::STATUS_NO_FIX);
  EXPECT_DOUBLE_EQ(fix.position_covariance[4], 25.0);  // north uncertainty on the ENU y axis
  EXPECT_EQ(fix.position_covariance_type, sensor_msgs::NavSatFix::COVARIANCE_TYPE_DIAGONAL_KNOWN);
}

TEST(PacketMessages, ImuRatesAreFrdOnTheOriginalTopicAndFluOnTheRep103One) {
  const VnBinaryData d = packet();
  const sensor_msgs::Imu pqr = vn200::to_imu_pqr(d, ros::Time(1, 0), "vn200_frd");
  EXPECT_FLOAT_EQ(pqr.angular_velocity.y, 0.2);
  EXPECT_EQ(pqr.header.frame_id, "vn200_frd");
  const sensor_msgs::Imu imu = vn200::to_imu(d, ros::Time(1, 0), "vn200");
  EXPECT_FLOAT_EQ(imu.angular_velocity.x, 0.1);
  EXPECT_FLOAT_EQ(imu.angular_velocity.y, -0.2);
  EXPECT_FLOAT_EQ(imu.angular_velocity.z, -0.3);
}

TEST(PacketMessages, AnEastboundAircraftFacesAlongEnuXWithOrWithoutTheQuaternion) {
  VnBinaryData d = packet();
  d.ypr_deg[1] = d.ypr_deg[2] = 0.0f;
  const sensor_msgs::Imu from_ypr = vn200::to_imu(d, ros::Time(1, 0), "vn200");
  const vn200::Quat q = vn200::attitude_ned(d);
  d.quat_xyzw[0] = static_cast<float>(q[0]);
  d.quat_xyzw[1] = static_cast<float>(q[1]);
  d.quat_xyzw[2] = static_cast<float>(q[2]);
  d.quat_xyzw[3] = static_cast<float>(q[3]);
  d.ypr_deg[0] = 0.0f;  // the quaternion wins when present
  d.has |= VN_HAS_QUATERNION;
  const sensor_msgs::Imu from_quat = vn200::to_imu(d, ros::Time(1, 0), "vn200");
  for (const sensor_msgs::Imu* imu : {&from_ypr, &from_quat}) {
    const auto& o = imu->orientation;
    const vn200::Vec3 nose = vn200::quat_rotate({o.x, o.y, o.z, o.w}, {1, 0, 0});
    EXPECT_NEAR(nose[0], 1.0, 1e-6);
    EXPECT_NEAR(nose[1], 0.0, 1e-6);
  }
}

TEST(PacketMessages, MagneticFieldPressureAndTemperatureInSiUnits) {
  VnBinaryData d = packet();
  d.mag_gauss[0] = 0.5f;
  d.pressure_kpa = 101.325f;
  d.temp_c = 21.5f;
  std_msgs::Header h;
  h.frame_id = "vn200";
  EXPECT_NEAR(vn200::to_magnetic_field(d, h).magnetic_field.x, 0.5e-4, 1e-10);
  EXPECT_NEAR(vn200::to_fluid_pressure(d, h).fluid_pressure, 101325.0, 0.01);
  EXPECT_FLOAT_EQ(vn200::to_temperature(d, h).temperature, 21.5);
  EXPECT_EQ(vn200::to_temperature(d, h).header.frame_id, "vn200");
}

// A level aircraft heading east, at the reference point, flying east at 20 m/s.
VnBinaryData level_eastbound() {
  VnBinaryData d = packet();
  d.ypr_deg[1] = d.ypr_deg[2] = 0.0f;
  d.vel_ned_mps[0] = 0.0f;
  d.vel_ned_mps[1] = 20.0f;
  d.vel_ned_mps[2] = 0.0f;
  d.angular_rate_radps[0] = d.angular_rate_radps[1] = d.angular_rate_radps[2] = 0.0f;
  return d;
}

TEST(PacketMessages, TheMountIsGivenInFrdAndPublishedInRep103Axes) {
  vn200::SensorMount m;
  m.x_m = 0.3;
  m.y_m = -0.1;      // left of the centre line
  m.z_m = 0.05;      // below
  m.yaw_deg = 90.0;  // the sensor's x points along the right wing
  const vn200::MountFlu flu = vn200::mount_flu(m);
  EXPECT_NEAR(flu.t_m[0], 0.3, 1e-12);
  EXPECT_NEAR(flu.t_m[1], 0.1, 1e-12);
  EXPECT_NEAR(flu.t_m[2], -0.05, 1e-12);
  const vn200::Vec3 sensor_x = vn200::quat_rotate(flu.q_base_sensor, {1, 0, 0});
  EXPECT_NEAR(sensor_x[0], 0.0, 1e-12);
  EXPECT_NEAR(sensor_x[1], -1.0, 1e-12);  // FLU: right is -y
  const geometry_msgs::TransformStamped tf =
      vn200::to_mount_transform(flu, ros::Time(1, 0), "base_link", "vn200");
  EXPECT_EQ(tf.header.frame_id, "base_link");
  EXPECT_EQ(tf.child_frame_id, "vn200");
  EXPECT_NEAR(tf.transform.translation.y, 0.1, 1e-12);
}

TEST(PacketMessages, TheFrdFrameIsTheSensorFrameTurnedAboutX) {
  const geometry_msgs::TransformStamped tf =
      vn200::to_frd_transform(ros::Time(1, 0), "vn200", "vn200_frd");
  const auto& q = tf.transform.rotation;
  const vn200::Vec3 frd_z = vn200::quat_rotate({q.x, q.y, q.z, q.w}, {0, 0, 1});
  EXPECT_NEAR(frd_z[2], -1.0, 1e-12);  // FRD's z (down) is FLU's -z
}

TEST(PacketMessages, BaseLinkIsTheSensorPoseWithTheMountTakenOff) {
  const VnBinaryData d = level_eastbound();
  // At the reference point, without a mount: base_link is the sensor.
  const vn200::BasePose at_ref =
      vn200::base_pose(d, vn200::MountFlu{}, d.lat_deg, d.lon_deg, d.alt_m);
  EXPECT_NEAR(at_ref.p_enu_m[0], 0.0, 1e-6);
  const vn200::BasePose above =
      vn200::base_pose(d, vn200::MountFlu{}, d.lat_deg, d.lon_deg, d.alt_m - 10.0);
  EXPECT_NEAR(above.p_enu_m[2], 10.0, 1e-6);
  // The sensor 1 m ahead of base_link: heading east, base_link is 1 m west of it.
  vn200::SensorMount ahead;
  ahead.x_m = 1.0;
  const vn200::BasePose behind =
      vn200::base_pose(d, vn200::mount_flu(ahead), d.lat_deg, d.lon_deg, d.alt_m);
  EXPECT_NEAR(behind.p_enu_m[0], -1.0, 1e-6);
  EXPECT_NEAR(behind.p_enu_m[1], 0.0, 1e-6);
  // The sensor turned 90 deg right on the airframe reads east: the airframe faces north.
  vn200::SensorMount turned;
  turned.yaw_deg = 90.0;
  const vn200::BasePose north =
      vn200::base_pose(d, vn200::mount_flu(turned), d.lat_deg, d.lon_deg, d.alt_m);
  const vn200::Vec3 nose = vn200::quat_rotate(north.q_enu_base, {1, 0, 0});
  EXPECT_NEAR(nose[0], 0.0, 1e-6);
  EXPECT_NEAR(nose[1], 1.0, 1e-6);
  EXPECT_GE(north.q_enu_base[3], 0.0);
  const geometry_msgs::TransformStamped tf =
      vn200::to_transform(ros::Time(1, 0), "odom", "base_link", north.p_enu_m, north.q_enu_base);
  EXPECT_EQ(tf.header.frame_id, "odom");
  EXPECT_EQ(tf.child_frame_id, "base_link");
}

TEST(PacketMessages, OdometryTwistIsInTheBodyWithTheLeverArmsSwingTakenOff) {
  VnBinaryData d = level_eastbound();
  d.angular_rate_radps[2] = 0.5f;  // yawing right (FRD r)
  vn200::SensorMount ahead;
  ahead.x_m = 1.0;
  const vn200::MountFlu mount = vn200::mount_flu(ahead);
  const vn200::BasePose pose = vn200::base_pose(d, mount, d.lat_deg, d.lon_deg, d.alt_m);
  const nav_msgs::Odometry odom =
      vn200::to_odometry(d, pose, mount, ros::Time(2, 0), "odom", "base_link", 0.0);
  EXPECT_EQ(odom.header.frame_id, "odom");
  EXPECT_EQ(odom.child_frame_id, "base_link");
  EXPECT_EQ(odom.header.stamp, ros::Time(2, 0));
  EXPECT_NEAR(odom.pose.pose.position.x, -1.0, 1e-6);
  // Forward at 20 m/s; the sensor 1 m ahead swings right at 0.5 m/s, base_link does not.
  EXPECT_NEAR(odom.twist.twist.linear.x, 20.0, 1e-5);
  EXPECT_NEAR(odom.twist.twist.linear.y, 0.5, 1e-6);
  EXPECT_NEAR(odom.twist.twist.linear.z, 0.0, 1e-6);
  EXPECT_NEAR(odom.twist.twist.angular.z, -0.5, 1e-6);  // FLU: a right turn is -z
}

TEST(PacketMessages, OdometryCovariancesComeFromTheInsUncertaintiesOrAreUnknown) {
  VnBinaryData d = level_eastbound();
  const vn200::BasePose pose = vn200::base_pose(d, vn200::MountFlu{}, 40.0, -88.0, 200.0);
  const nav_msgs::Odometry unknown =
      vn200::to_odometry(d, pose, vn200::MountFlu{}, ros::Time(1, 0), "odom", "base_link", 0.0);
  for (const double c : unknown.pose.covariance) EXPECT_EQ(c, 0.0);
  d.has |= VN_HAS_INS_POS_UNC | VN_HAS_YPR_UNC | VN_HAS_INS_VEL_UNC;
  d.ins_pos_unc_m = 2.0f;
  d.ins_vel_unc_mps = 0.5f;
  d.ypr_unc_deg[0] = 2.0f;  // yaw
  d.ypr_unc_deg[1] = 1.0f;  // pitch
  d.ypr_unc_deg[2] = 0.5f;  // roll
  const double rate_var = vn200::gyro_rate_variance(100.0);
  const nav_msgs::Odometry odom = vn200::to_odometry(d, pose, vn200::MountFlu{}, ros::Time(1, 0),
                                                     "odom", "base_link", rate_var);
  for (const int i : {0, 7, 14}) EXPECT_FLOAT_EQ(odom.pose.covariance[i], 4.0);
  EXPECT_NEAR(odom.pose.covariance[21], std::pow(0.5 * kPi / 180.0, 2), 1e-12);  // roll
  EXPECT_NEAR(odom.pose.covariance[28], std::pow(1.0 * kPi / 180.0, 2), 1e-12);  // pitch
  EXPECT_NEAR(odom.pose.covariance[35], std::pow(2.0 * kPi / 180.0, 2), 1e-12);  // yaw
  EXPECT_EQ(odom.pose.covariance[1], 0.0);
  for (const int i : {0, 7, 14}) EXPECT_FLOAT_EQ(odom.twist.covariance[i], 0.25);
  for (const int i : {21, 28, 35}) EXPECT_DOUBLE_EQ(odom.twist.covariance[i], rate_var);
  // 0.0035 deg/s/sqrt(Hz) over 50 Hz: 0.025 deg/s one sigma.
  EXPECT_NEAR(std::sqrt(rate_var) * 180.0 / kPi, 0.0035 * std::sqrt(50.0), 1e-9);
}

}  // namespace
