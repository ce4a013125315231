// ROS node for the VectorNav VN-200: owns the port (or a replay file), runs a SensorSession,
// and turns decoded packets into the original drone_ros topics and REP-103/105 ones.
#pragma once

#include <diagnostic_updater/diagnostic_updater.h>
#include <diagnostic_updater/update_functions.h>
#include <drone_ros/HomePosition.h>
#include <ros/ros.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_broadcaster.h>

#include <memory>
#include <mutex>
#include <string>

#include "drone_ros_common/serial_port.h"
#include "node_params.h"
#include "sensor_session.h"
#include "time_mapper.h"

namespace vn200 {

class Vn200Node {
 public:
  Vn200Node(ros::NodeHandle nh, ros::NodeHandle pnh, const NodeParams& params);
  // Runs until ROS shuts down. Returns a process exit code.
  int run();

 private:
  int run_port();
  int run_replay();
  void try_open(double now_s);
  void link_lost(const std::string& why, double now_s);
  void pace_replay(const VnBinaryData& d);  // replay only: sleeps until the packet's sensor time
  void publish_packet(const VnBinaryData& d);
  void publish_link_down();
  void diag_link(diagnostic_updater::DiagnosticStatusWrapper& stat);

  ros::NodeHandle nh_, pnh_;
  NodeParams params_;
  SensorSession session_;
  drone_ros_common::SerialPort port_;
  TimeMapper time_mapper_;
  diagnostic_updater::Updater diag_;
  // The /ins stream's rate against the configured output rate (x the replay speed): a lab's
  // rqt_runtime_monitor shows a sensor running slow or stalled, not just a link up or down.
  double ins_rate_hz_ = 0.0;
  std::unique_ptr<diagnostic_updater::FrequencyStatus> ins_rate_;
  // REP-105: as the one source of the navigation solution this node owns the aircraft's tree:
  // map -> odom (identity, static), odom -> base_link (each solution), base_link -> frame_id (the
  // mount, static) and frame_id -> frd_frame_id (static).
  tf2_ros::TransformBroadcaster tf_;
  std::unique_ptr<tf2_ros::StaticTransformBroadcaster> static_tf_;
  MountFlu mount_;
  double angular_rate_var_ = 0.0;

  // A replay that must reach its subscribers whole starts only once they are all connected.
  bool every_data_topic_subscribed() const;
  ros::Publisher ins_pub_, gps_position_pub_, gps_velocity_pub_, imu_pqr_pub_, attitude_pub_;
  ros::Publisher imu_pub_, fix_pub_, velocity_pub_, mag_pub_, pressure_pub_, temperature_pub_;
  ros::Publisher odom_pub_;

  bool link_up_ = false;  // decoded packets are arriving
  double next_open_s_ = 0.0;
  double next_down_report_s_ = 0.0;
  double opened_at_s_ = 0.0;
  unsigned reconnects_ = 0;
  unsigned link_losses_ = 0;
  std::string last_problem_;
  // map's origin is home, from its one owner (the HA, on the latched /home): no tf before it.
  void on_home(const drone_ros::HomePosition::ConstPtr& msg);
  ros::Subscriber home_sub_;
  std::mutex ref_mutex_;
  bool have_ref_ = false;
  double ref_lat_deg_ = 0, ref_lon_deg_ = 0, ref_alt_m_ = 0;
  // Replay pacing.
  bool replay_started_ = false;
  double replay_t0_sensor_s_ = 0, replay_t0_wall_s_ = 0;
  bool replay_done_ = false;
};

}  // namespace vn200
