// One decoded VN-200 binary packet as the ROS messages the node publishes: pure converters, no
// publishing, no clock (the stamp is passed in), so each is unit-tested on its own
// (test/test_packet_messages.cpp). Which ones are published for a packet depends on the fields
// it carries (VnBinaryData::has): the node decides that.
#pragma once

#include <drone_ros/ins.h>
#include <geometry_msgs/Point.h>
#include <geometry_msgs/TransformStamped.h>
#include <geometry_msgs/Twist.h>
#include <geometry_msgs/TwistStamped.h>
#include <nav_msgs/Odometry.h>
#include <ros/time.h>
#include <sensor_msgs/FluidPressure.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/MagneticField.h>
#include <sensor_msgs/NavSatFix.h>
#include <sensor_msgs/Temperature.h>
#include <std_msgs/Header.h>

#include <string>

#include "conversions.h"
#include "vn_binary.h"

namespace vn200 {

// Body(FRD) relative to NED: the packet's quaternion, or one from its yaw, pitch and roll.
Quat attitude_ned(const VnBinaryData& d);

// --- Original drone_ros topics (the thesis's controller reads these) ---
// GPS time of week and week (from the GPS group, else from GPS time), status, satellites, fix.
drone_ros::ins to_ins(const VnBinaryData& d, const ros::Time& stamp, const std::string& frame_id);
// phi, theta, psi [rad] in x, y, z.
geometry_msgs::Point to_attitude(const VnBinaryData& d);
// north, east, down [m/s] in linear.
geometry_msgs::Twist to_gps_velocity(const VnBinaryData& d);
// Body rates P, Q, R and specific force in the sensor's own (FRD) axes, attitude relative to NED.
sensor_msgs::Imu to_imu_pqr(const VnBinaryData& d, const ros::Time& stamp,
                            const std::string& frd_frame_id);

// --- REP-103/105 topics ---
// Position with the INS uncertainty (approximated), else the GPS one (diagonal known).
sensor_msgs::NavSatFix to_nav_sat_fix(const VnBinaryData& d, const ros::Time& stamp,
                                      const std::string& frame_id);
// Velocity in ENU.
geometry_msgs::TwistStamped to_velocity_enu(const VnBinaryData& d, const ros::Time& stamp,
                                            const std::string& world_frame_id);
// Attitude FLU relative to ENU with its uncertainty, rates and acceleration in FLU.
sensor_msgs::Imu to_imu(const VnBinaryData& d, const ros::Time& stamp, const std::string& frame_id);
sensor_msgs::MagneticField to_magnetic_field(const VnBinaryData& d, const std_msgs::Header& header);
sensor_msgs::FluidPressure to_fluid_pressure(const VnBinaryData& d, const std_msgs::Header& header);
sensor_msgs::Temperature to_temperature(const VnBinaryData& d, const std_msgs::Header& header);
// --- REP-105 frames: map -> odom -> base_link -> vn200 (-> vn200_frd) ---
// Where the sensor sits on the airframe, as aircraft/<name>/vn200_mount.yaml gives it: its
// reference point from base_link's origin in body FRD metres (the airframe file's axes), and its
// axes' yaw, pitch, roll (3-2-1) relative to the body's.
struct SensorMount {
  double x_m = 0.0, y_m = 0.0, z_m = 0.0;
  double roll_deg = 0.0, pitch_deg = 0.0, yaw_deg = 0.0;
};
// The same mount in REP-103 axes: the sensor's origin in base_link (FLU) and the rotation taking
// sensor (FLU) vectors into base_link.
struct MountFlu {
  Vec3 t_m{0.0, 0.0, 0.0};
  Quat q_base_sensor{0.0, 0.0, 0.0, 1.0};
};
MountFlu mount_flu(const SensorMount& mount);

// base_link's pose in the local ENU frame anchored at (ref_lat_deg, ref_lon_deg, ref_alt_m): the
// INS solution is the sensor's, so the mount is taken off it.
struct BasePose {
  Vec3 p_enu_m{0.0, 0.0, 0.0};
  Quat q_enu_base{0.0, 0.0, 0.0, 1.0};
};
BasePose base_pose(const VnBinaryData& d, const MountFlu& mount, double ref_lat_deg,
                   double ref_lon_deg, double ref_alt_m);

geometry_msgs::TransformStamped to_transform(const ros::Time& stamp, const std::string& parent,
                                             const std::string& child, const Vec3& t_m,
                                             const Quat& q);
// The static ones: base_link -> sensor (the mount) and sensor -> its FRD twin (a half turn about
// x, so the FRD topics' frame is in the tree too).
geometry_msgs::TransformStamped to_mount_transform(const MountFlu& mount, const ros::Time& stamp,
                                                   const std::string& base_frame_id,
                                                   const std::string& frame_id);
geometry_msgs::TransformStamped to_frd_transform(const ros::Time& stamp,
                                                 const std::string& frame_id,
                                                 const std::string& frd_frame_id);

// Variance [rad^2/s^2] of one angular-rate sample: the VN-200 reports no rate uncertainty, so the
// datasheet's gyro noise density (0.0035 deg/s/sqrt(Hz)) over the output's bandwidth (rate_hz/2).
double gyro_rate_variance(double rate_hz);
// nav_msgs/Odometry of base_link: pose in odom (ENU metres, as `pose`), twist in base_link
// (REP-103 body FLU: the mount's lever arm taken off the sensor's velocity). Covariances from the
// packet's INS uncertainties (position, velocity: isotropic; attitude: roll, pitch, yaw) and
// `angular_rate_var`; a block the packet has no uncertainty for is all zero (unknown).
nav_msgs::Odometry to_odometry(const VnBinaryData& d, const BasePose& pose, const MountFlu& mount,
                               const ros::Time& stamp, const std::string& odom_frame_id,
                               const std::string& base_frame_id, double angular_rate_var);

}  // namespace vn200
