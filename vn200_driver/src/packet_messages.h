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
// The sensor's pose in a local ENU frame anchored at (ref_lat_deg, ref_lon_deg, ref_alt_m).
geometry_msgs::TransformStamped to_transform(const VnBinaryData& d, const ros::Time& stamp,
                                             const std::string& world_frame_id,
                                             const std::string& frame_id, double ref_lat_deg,
                                             double ref_lon_deg, double ref_alt_m);

}  // namespace vn200
