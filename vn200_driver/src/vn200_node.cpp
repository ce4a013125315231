#include "vn200_node.h"

#include <algorithm>
#include <fstream>
#include <thread>

#include "output_config.h"
#include "packet_messages.h"
#include "vn_command.h"

namespace vn200 {

namespace {

SensorSession::Options session_options(const NodeParams& p) {
  SensorSession::Options o;
  o.output =
      node_output_config(static_cast<unsigned>(p.rate_hz), static_cast<VnAsyncMode>(p.sensor_port),
                         static_cast<unsigned>(p.binary_output));
  o.response_timeout_s = p.response_timeout_s;
  return o;
}

double wall_now() { return ros::WallTime::now().toSec(); }

}  // namespace

Vn200Node::Vn200Node(ros::NodeHandle nh, ros::NodeHandle pnh, const NodeParams& params)
    : nh_(nh), pnh_(pnh), params_(params), session_(session_options(params)) {
  // Original drone_ros interface (thesis): the names and types the controller subscribes to,
  // relative, so an aircraft launched in a namespace (<group ns="uav1">) keeps its own.
  ins_pub_ = nh_.advertise<drone_ros::ins>("ins", 10);
  gps_position_pub_ = nh_.advertise<sensor_msgs::NavSatFix>("gps_position", 10);
  gps_velocity_pub_ = nh_.advertise<geometry_msgs::Twist>("gps_velocity", 10);
  imu_pqr_pub_ = nh_.advertise<sensor_msgs::Imu>("imu_PQR_acceleration", 10);
  attitude_pub_ = nh_.advertise<geometry_msgs::Point>("attitude", 10);
  // The aircraft's odometry (REP-105's odom -> base_link as a message), beside /ins.
  odom_pub_ = nh_.advertise<nav_msgs::Odometry>("odom", 10);
  // REP-103/105 topics under the node's private namespace.
  imu_pub_ = pnh_.advertise<sensor_msgs::Imu>("imu/data", 10);
  fix_pub_ = pnh_.advertise<sensor_msgs::NavSatFix>("fix", 10);
  velocity_pub_ = pnh_.advertise<geometry_msgs::TwistStamped>("velocity", 10);
  mag_pub_ = pnh_.advertise<sensor_msgs::MagneticField>("imu/mag", 10);
  pressure_pub_ = pnh_.advertise<sensor_msgs::FluidPressure>("pressure", 10);
  temperature_pub_ = pnh_.advertise<sensor_msgs::Temperature>("temperature", 10);
  // Odometry needs map's origin too, so home is always listened to.
  home_sub_ = nh_.subscribe("home", 1, &Vn200Node::on_home, this);
  mount_ = mount_flu(params_.mount);
  angular_rate_var_ = gyro_rate_variance(params_.rate_hz);
  if (params_.publish_tf) {
    // Static: latched on /tf_static, so a viewer started later has them; they do not wait for
    // home, since neither depends on where map's origin is.
    static_tf_ = std::make_unique<tf2_ros::StaticTransformBroadcaster>();
    const ros::Time now = ros::Time::now();
    static_tf_->sendTransform(
        {to_transform(now, params_.map_frame_id, params_.odom_frame_id, {0.0, 0.0, 0.0},
                      {0.0, 0.0, 0.0, 1.0}),
         to_mount_transform(mount_, now, params_.base_frame_id, params_.frame_id),
         to_frd_transform(now, params_.frame_id, params_.frd_frame_id)});
  }

  diag_.setHardwareID(params_.replay_file.empty() ? "VN-200 on " + params_.port
                                                  : "VN-200 replay " + params_.replay_file);
  diag_.add("VN-200 link", this, &Vn200Node::diag_link);
  ins_rate_hz_ = params_.rate_hz * (params_.replay_file.empty() ? 1.0 : params_.replay_speed);
  // A window of 3 updates (2 s at the updater's 1 Hz): long enough to average a USB frame's
  // bunching, short enough to show a stall within seconds.
  ins_rate_ = std::make_unique<diagnostic_updater::FrequencyStatus>(
      diagnostic_updater::FrequencyStatusParam(&ins_rate_hz_, &ins_rate_hz_, 0.1, 3), "/ins rate");
  diag_.add(*ins_rate_);

  session_.on_binary = [this](const VnBinaryData& d, double) {
    if (!params_.replay_file.empty()) pace_replay(d);
    publish_packet(d);
  };
}

int Vn200Node::run() { return params_.replay_file.empty() ? run_port() : run_replay(); }

void Vn200Node::try_open(double now_s) {
  std::string error;
  if (params_.sensor_baud != 0 && params_.sensor_baud != params_.baud) {
    // The sensor may be at its power-up speed: ask it, at that speed, to switch to ours. If it
    // is already at ours (reconnect without a power cycle), these bytes are noise to it.
    char cmd[VN_CMD_MAX];
    const size_t n =
        vn_cmd_set_baud(cmd, sizeof cmd, static_cast<uint32_t>(params_.baud), VN_CK_XOR8);
    if (port_.open(params_.port, params_.sensor_baud, &error) && n > 0 && port_.write_all(cmd, n)) {
      uint8_t sink[256];
      size_t got = 0;
      const ros::WallTime until = ros::WallTime::now() + ros::WallDuration(0.1);
      using Read = drone_ros_common::SerialPort::ReadResult;
      while (ros::WallTime::now() < until &&
             port_.read(sink, sizeof sink, 20, &got) != Read::kGone) {
      }  // let the reply (at the old speed) go by before changing ours
    }
    port_.close();
  }
  if (!port_.open(params_.port, params_.baud, &error)) {
    if (last_problem_ != error) ROS_WARN("vn200: cannot open port: %s", error.c_str());
    last_problem_ = error;
    next_open_s_ = now_s + params_.reconnect_period_s;
    return;
  }
  ROS_INFO("vn200: opened %s at %d baud, configuring", params_.port.c_str(), params_.baud);
  ++reconnects_;
  opened_at_s_ = now_s;
  time_mapper_.reset();  // the sensor may have rebooted while away
  session_.start(now_s);
}

void Vn200Node::link_lost(const std::string& why, double now_s) {
  ROS_WARN("vn200: link lost (%s); reconnecting every %.1f s", why.c_str(),
           params_.reconnect_period_s);
  last_problem_ = why;
  port_.close();
  if (link_up_) ++link_losses_;
  link_up_ = false;
  next_open_s_ = now_s + params_.reconnect_period_s;
  next_down_report_s_ = now_s;
}

void Vn200Node::publish_link_down() {
  drone_ros::ins msg;
  msg.header.stamp = ros::Time::now();
  msg.header.frame_id = params_.frame_id;
  msg.usbstatus = 0;
  ins_pub_.publish(msg);
}

int Vn200Node::run_port() {
  uint8_t buf[4096];
  next_down_report_s_ = wall_now();
  while (ros::ok()) {
    const double now = wall_now();
    if (!port_.is_open()) {
      if (now >= next_open_s_) try_open(now);
      if (!port_.is_open()) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    } else {
      const std::string cmd = session_.poll_command(now);
      if (!cmd.empty() && !port_.write_all(cmd.data(), cmd.size())) {
        link_lost("write failed", now);
      } else if (session_.state() == SensorSession::State::Failed) {
        link_lost("sensor did not accept the configuration", now);
      } else {
        size_t got = 0;
        const auto r = port_.read(buf, sizeof buf, 20, &got);
        if (r == drone_ros_common::SerialPort::ReadResult::kGone) {
          link_lost("device gone", now);
        } else if (r == drone_ros_common::SerialPort::ReadResult::kData) {
          session_.on_bytes(buf, got, wall_now());
        }
        // A port that stays open but silent (sensor power-cycled, cable half-plugged): report it
        // at once, and reopen/reconfigure if it persists.
        const double last = std::max(session_.last_byte_s(), opened_at_s_);
        if (port_.is_open() && now - last > params_.data_timeout_s) {
          if (link_up_) {
            ++link_losses_;
            last_problem_ = "no data";
          }
          link_up_ = false;
          if (now - last > 3 * params_.data_timeout_s) link_lost("no data", now);
        }
      }
    }
    if (!link_up_ && now >= next_down_report_s_) {
      publish_link_down();
      next_down_report_s_ = now + 1.0;
    }
    ros::spinOnce();
    diag_.update();
  }
  return 0;
}

bool Vn200Node::every_data_topic_subscribed() const {
  for (const ros::Publisher* pub :
       {&ins_pub_, &gps_position_pub_, &gps_velocity_pub_, &imu_pqr_pub_, &attitude_pub_, &imu_pub_,
        &fix_pub_, &velocity_pub_, &mag_pub_, &pressure_pub_, &temperature_pub_, &odom_pub_}) {
    if (pub->getNumSubscribers() == 0) return false;
  }
  return true;
}

int Vn200Node::run_replay() {
  std::ifstream in(params_.replay_file, std::ios::binary);
  if (!in) {
    ROS_FATAL("vn200: cannot open replay file %s", params_.replay_file.c_str());
    return 1;
  }
  ROS_INFO("vn200: replaying %s at %.2fx", params_.replay_file.c_str(), params_.replay_speed);
  const ros::WallTime start_at = ros::WallTime::now() + ros::WallDuration(params_.replay_delay_s);
  while (ros::ok() && (ros::WallTime::now() < start_at ||
                       (params_.replay_wait_for_subscribers && !every_data_topic_subscribed()))) {
    ros::spinOnce();
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  char buf[256];
  while (ros::ok()) {
    if (!replay_done_) {
      in.read(buf, sizeof buf);
      const std::streamsize n = in.gcount();
      if (n > 0)
        session_.on_bytes(reinterpret_cast<const uint8_t*>(buf), static_cast<size_t>(n),
                          wall_now());
      if (!in) {
        if (params_.replay_loop) {
          in.clear();
          in.seekg(0);
          replay_started_ = false;
          time_mapper_.reset();
        } else {
          replay_done_ = true;
          link_up_ = false;
          ROS_INFO("vn200: replay finished (%llu packets)",
                   static_cast<unsigned long long>(session_.counters().packets_decoded));
        }
      }
    } else {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    ros::spinOnce();
    diag_.update();
  }
  return 0;
}

void Vn200Node::pace_replay(const VnBinaryData& d) {
  // Hold each packet until its sensor time comes round again.
  if (!(d.has & VN_HAS_TIME_STARTUP)) return;
  const double t = static_cast<double>(d.time_startup_ns) * 1e-9;
  if (!replay_started_ || t < replay_t0_sensor_s_) {
    replay_started_ = true;
    replay_t0_sensor_s_ = t;
    replay_t0_wall_s_ = wall_now();
  }
  const double due = replay_t0_wall_s_ + (t - replay_t0_sensor_s_) / params_.replay_speed;
  const double wait = due - wall_now();
  if (wait > 0) ros::WallDuration(std::min(wait, 10.0)).sleep();
}

void Vn200Node::publish_packet(const VnBinaryData& d) {
  link_up_ = true;
  ros::Time stamp = ros::Time::now();
  if (d.has & VN_HAS_TIME_STARTUP) {
    const double mapped =
        time_mapper_.map(static_cast<double>(d.time_startup_ns) * 1e-9, stamp.toSec());
    if (mapped > 0 && mapped < 4.0e9) stamp = ros::Time(mapped);  // ros::Time throws outside
  }

  // Original topics.
  ins_pub_.publish(to_ins(d, stamp, params_.frame_id));
  ins_rate_->tick();
  if (d.has & VN_HAS_YPR) attitude_pub_.publish(to_attitude(d));
  if (d.has & VN_HAS_POSITION_LLA) {
    const sensor_msgs::NavSatFix fix = to_nav_sat_fix(d, stamp, params_.frame_id);
    gps_position_pub_.publish(fix);
    fix_pub_.publish(fix);
  }
  if (d.has & VN_HAS_VEL_NED) {
    gps_velocity_pub_.publish(to_gps_velocity(d));
    velocity_pub_.publish(to_velocity_enu(d, stamp, params_.odom_frame_id));
  }
  if (d.has & VN_HAS_ANGULAR_RATE) imu_pqr_pub_.publish(to_imu_pqr(d, stamp, params_.frd_frame_id));

  // REP-103 topics.
  const sensor_msgs::Imu imu = to_imu(d, stamp, params_.frame_id);
  if (d.has & (VN_HAS_QUATERNION | VN_HAS_YPR)) imu_pub_.publish(imu);
  if (d.has & VN_HAS_MAG) mag_pub_.publish(to_magnetic_field(d, imu.header));
  if (d.has & VN_HAS_PRESSURE) pressure_pub_.publish(to_fluid_pressure(d, imu.header));
  if (d.has & VN_HAS_TEMP) temperature_pub_.publish(to_temperature(d, imu.header));

  // odom -> base_link and the odometry: ENU anchored at home, the stack's one origin (/home,
  // from the HA), once the INS has a solution (mode 1 or 2).
  double ref_lat_deg, ref_lon_deg, ref_alt_m;
  bool have_ref;
  {
    std::lock_guard<std::mutex> lock(ref_mutex_);
    have_ref = have_ref_;
    ref_lat_deg = ref_lat_deg_;
    ref_lon_deg = ref_lon_deg_;
    ref_alt_m = ref_alt_m_;
  }
  constexpr uint32_t kPoseFields = VN_HAS_POSITION_LLA | VN_HAS_VEL_NED | VN_HAS_ANGULAR_RATE;
  if (have_ref && (d.has & kPoseFields) == kPoseFields &&
      (d.has & (VN_HAS_QUATERNION | VN_HAS_YPR)) && VN_INS_STATUS_MODE(d.ins_status) >= 1) {
    const BasePose pose = base_pose(d, mount_, ref_lat_deg, ref_lon_deg, ref_alt_m);
    odom_pub_.publish(to_odometry(d, pose, mount_, stamp, params_.odom_frame_id,
                                  params_.base_frame_id, angular_rate_var_));
    if (params_.publish_tf) {
      tf_.sendTransform(to_transform(stamp, params_.odom_frame_id, params_.base_frame_id,
                                     pose.p_enu_m, pose.q_enu_base));
    }
  }
}

void Vn200Node::diag_link(diagnostic_updater::DiagnosticStatusWrapper& stat) {
  const VnFramerStats& f = session_.framer_stats();
  const SensorSession::Counters& c = session_.counters();
  if (params_.replay_file.empty() && !port_.is_open()) {
    stat.summary(diagnostic_msgs::DiagnosticStatus::ERROR, "port closed: " + last_problem_);
  } else if (!link_up_ && !replay_done_) {
    stat.summary(diagnostic_msgs::DiagnosticStatus::ERROR, "no data from the sensor");
  } else if (session_.state() == SensorSession::State::Configuring) {
    stat.summary(diagnostic_msgs::DiagnosticStatus::WARN, "configuring the sensor");
  } else {
    stat.summary(diagnostic_msgs::DiagnosticStatus::OK,
                 replay_done_ ? "replay finished" : "streaming");
  }
  stat.add("usbstatus", link_up_ ? 1 : 0);
  stat.add("packets decoded", c.packets_decoded);
  stat.add("bad packets", session_.bad_packets());
  stat.add("bad binary CRC", f.bad_binary_crc);
  stat.add("bad binary groups", f.bad_binary_groups);
  stat.add("bad binary field", f.bad_binary_field);
  stat.add("bad ASCII checksum", f.bad_ascii_checksum);
  stat.add("bad ASCII character", f.bad_ascii_char);
  stat.add("ASCII too long", f.bad_ascii_too_long);
  stat.add("binary decode errors", c.binary_decode_errors);
  stat.add("ASCII decode errors", c.ascii_decode_errors);
  stat.add("dropped bytes", f.dropped_bytes);
  stat.add("bytes received", c.bytes);
  stat.add("sensor errors", c.sensor_errors);
  stat.add("last sensor error", sensor_error_text(c.last_sensor_error));
  stat.add("configuration resends", c.config_resends);
  stat.add("connections", reconnects_);
  stat.add("link losses", link_losses_);
  stat.add("time offset resets", time_mapper_.resets());
  stat.add("last problem", last_problem_);
}

void Vn200Node::on_home(const drone_ros::HomePosition::ConstPtr& msg) {
  if (!is_valid_home(msg->latitude, msg->longitude, msg->altitude)) {
    ROS_WARN("vn200: home %u dropped: not a valid position", msg->seq);
    return;
  }
  std::lock_guard<std::mutex> lock(ref_mutex_);
  have_ref_ = true;
  ref_lat_deg_ = msg->latitude;
  ref_lon_deg_ = msg->longitude;
  ref_alt_m_ = msg->altitude;
}

}  // namespace vn200
