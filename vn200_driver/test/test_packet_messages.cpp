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

TEST(PacketMessages, TransformIsTheOffsetFromTheReferencePoint) {
  VnBinaryData d = packet();
  const geometry_msgs::TransformStamped at_ref =
      vn200::to_transform(d, ros::Time(1, 0), "map", "vn200", d.lat_deg, d.lon_deg, d.alt_m);
  EXPECT_NEAR(at_ref.transform.translation.x, 0.0, 1e-6);
  EXPECT_NEAR(at_ref.transform.translation.z, 0.0, 1e-6);
  const geometry_msgs::TransformStamped above =
      vn200::to_transform(d, ros::Time(1, 0), "map", "vn200", d.lat_deg, d.lon_deg, d.alt_m - 10.0);
  EXPECT_NEAR(above.transform.translation.z, 10.0, 1e-6);
  EXPECT_EQ(above.child_frame_id, "vn200");
  EXPECT_EQ(above.header.frame_id, "map");
}

}  // namespace
