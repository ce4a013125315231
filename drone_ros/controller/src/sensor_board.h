// The latest value of every topic controller_<aircraft> listens to, with the monotonic time it
// arrived, turned into the GNC's input once per step. Messages with a NaN or infinity are
// counted and dropped here, never stored. While the pilot is in command the RC positions are
// captured as trims, as the original node did. No ROS calls: the node passes times in.
#ifndef CONTROLLER_SENSOR_BOARD_H
#define CONTROLLER_SENSOR_BOARD_H

#include <drone_ros/ins.h>
#include <drone_ros/pwm.h>
#include <drone_ros/way.h>
#include <geometry_msgs/Point.h>
#include <geometry_msgs/Twist.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/NavSatFix.h>

#include <array>
#include <cstdint>
#include <initializer_list>

#include "controller_params.h"

namespace controller {

// The links the command's sensor_links_healthy vouches for.
enum Link : uint32_t {
  kLinkPwm = 0,      // /pwm: the HA computer (RC, pitot), and its usbstatus
  kLinkIns,          // /ins: the VN-200 link status
  kLinkGpsPosition,  // /gps_position
  kLinkGpsVelocity,  // /gps_velocity
  kLinkImu,          // /imu_PQR_acceleration
  kLinkAttitude,     // /attitude
  kLinkCount
};

const char *link_name(Link link);

class SensorBoard {
 public:
  explicit SensorBoard(const ControllerParams &params);
  // A new parameter set while running (a tunable changed from the ground).
  void apply_params(const ControllerParams &params);

  // Each returns false if the message was dropped (not finite).
  bool on_pwm(const drone_ros::pwm &msg, double now_s);
  bool on_ins(const drone_ros::ins &msg, double now_s);
  bool on_gps_position(const sensor_msgs::NavSatFix &msg, double now_s);
  bool on_gps_velocity(const geometry_msgs::Twist &msg, double now_s);
  bool on_imu(const sensor_msgs::Imu &msg, double now_s);
  bool on_attitude(const geometry_msgs::Point &msg, double now_s);
  bool on_way(const drone_ros::way &msg);
  bool on_pressure(double pressure_pa);
  bool on_battery(double voltage_v);

  // Bit i set when link i is stale (older than the timeout), missing, or reports itself down.
  uint32_t unhealthy_links(double now_s) const;
  // The most recent arrival of any of the links, for the latency benchmark and diagnostics.
  double last_arrival_s() const { return last_arrival_s_; }

  void fill_input(GncInput *in) const;

  const drone_ros::pwm &pwm() const { return pwm_; }
  const drone_ros::ins &ins() const { return ins_; }
  const sensor_msgs::NavSatFix &gps_position() const { return gps_position_; }
  const geometry_msgs::Twist &gps_velocity() const { return gps_velocity_; }
  const sensor_msgs::Imu &imu() const { return imu_; }
  const geometry_msgs::Point &attitude() const { return attitude_; }
  double pressure_pa() const { return pressure_pa_; }
  double voltage_v() const { return voltage_v_; }
  bool home_valid() const { return home_valid_; }
  struct Home {
    double lat_deg, lon_deg, alt_m;
  };
  Home home() const { return {home_lat_deg_, home_lon_deg_, home_alt_m_}; }
  // Home from its one owner, the HA (/home, latched): the origin of /way's frame. It replaces
  // any earlier home (a SET_HOME on the ground); a position that is not finite or out of range
  // is dropped and the old home kept. Returns whether it was taken.
  bool on_home(double lat_deg, double lon_deg, double alt_m);
  // Every sensor link has delivered at least one message since the node started.
  bool all_seen() const;
  // Every message seen so far counts as arrived at now_s (a lockstep start).
  void restamp_arrivals(double now_s);
  bool home_cmd() const { return params_.home_cmd; }
  uint32_t dropped_messages() const { return dropped_; }
  uint32_t dropped_waypoint_plans() const { return dropped_plans_; }
  // Trims in use: the parameters until the pilot flies, then the RC positions.
  double throttle_trim() const { return throttle_trim_; }
  double elevator_trim_rad() const { return elevator_trim_rad_; }
  double aileron_trim_rad() const { return aileron_trim_rad_; }
  double rudder_trim_rad() const { return rudder_trim_rad_; }

 private:
  void arrived(Link link, double now_s);
  bool drop();
  // msg into slot as link's arrival at now_s if every one of values is finite, else dropped.
  template <typename Msg>
  bool take(const Msg &msg, std::initializer_list<double> values, Msg *slot, Link link,
            double now_s);

  ControllerParams params_;
  std::array<double, kLinkCount> arrival_s_{};
  std::array<bool, kLinkCount> seen_{};
  double last_arrival_s_ = 0.0;
  drone_ros::pwm pwm_;
  drone_ros::ins ins_;
  sensor_msgs::NavSatFix gps_position_;
  geometry_msgs::Twist gps_velocity_;
  sensor_msgs::Imu imu_;
  geometry_msgs::Point attitude_;
  drone_ros::way way_;
  uint32_t way_revision_ = 0;
  double pressure_pa_ = 0.0;
  double voltage_v_ = 0.0;
  bool home_valid_ = false;
  double home_lat_deg_ = 0.0, home_lon_deg_ = 0.0, home_alt_m_ = 0.0;
  double throttle_trim_, elevator_trim_rad_, aileron_trim_rad_, rudder_trim_rad_;
  uint32_t dropped_ = 0;
  uint32_t dropped_plans_ = 0;
};

}  // namespace controller

#endif
