// microhard_gs: thin ROS shell around GsCore. Subscribes /data and /decision_status, publishes
// /way, /operator_command and diagnostics, and moves bytes between the link and the core.
#include <diagnostic_updater/diagnostic_updater.h>
#include <drone_ros/DecisionStatus.h>
#include <drone_ros/HomePosition.h>
#include <drone_ros/OperatorCommand.h>
#include <drone_ros/SetTunable.h>
#include <drone_ros/data.h>
#include <drone_ros/way.h>
#include <drone_ros_common/node_main.h>
#include <ros/ros.h>
#include <ros/serialization.h>

#include <array>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

#include "gs_core.h"
#include "hp_command.h"
#include "node_config.h"
#include "serial_transport.h"
#include "tlog_writer.h"
#include "udp_transport.h"

namespace microhard_gs {
namespace {

// How often the tlog's buffer goes to the file: what a crash of the node can lose, at one
// write(2) of a few KB (telemetry at 10 Hz is about 3 KB/s).
constexpr uint64_t kTlogFlushPeriodMs = 500;

static_assert(kControllerHp == drone_ros::DecisionStatus::CONTROLLER_HP &&
                  kControllerHa == drone_ros::DecisionStatus::CONTROLLER_HA &&
                  kControllerRecovering == drone_ros::DecisionStatus::CONTROLLER_RECOVERING &&
                  kControllerHaLatched == drone_ros::DecisionStatus::CONTROLLER_HA_LATCHED &&
                  kControllerManual == drone_ros::DecisionStatus::CONTROLLER_MANUAL,
              "gs_core.h's ControllerId must number controllers as DecisionStatus does");

Clock now_clock() {
  using namespace std::chrono;
  Clock c;
  c.mono_ms = static_cast<uint64_t>(
      duration_cast<milliseconds>(steady_clock::now().time_since_epoch()).count());
  c.unix_us = static_cast<uint64_t>(
      duration_cast<microseconds>(system_clock::now().time_since_epoch()).count());
  return c;
}

// msg/OperatorCommand.msg's crc32: CRC-32 over the message's own ROS serialization before it
// (the HA's link checks it and drops a request that changed on the way, which rosserial's 8-bit
// sum can miss). Computed from the serialization, not from a second copy of the field list.
void seal(drone_ros::OperatorCommand* c) {
  static_assert(ros::message_traits::IsFixedSize<drone_ros::OperatorCommand>::value,
                "OperatorCommand is fixed size: its serialization is the CRC'd fields and the CRC");
  std::array<uint8_t, HA_OPERATOR_COMMAND_FIELDS_LEN + sizeof c->crc32> bytes{};
  c->crc32 = 0;
  ros::serialization::OStream out(bytes.data(), static_cast<uint32_t>(bytes.size()));
  ros::serialization::serialize(out, *c);
  c->crc32 = ha_crc32(bytes.data(), HA_OPERATOR_COMMAND_FIELDS_LEN);
}

Telemetry to_telemetry(const drone_ros::data& d) {
  Telemetry t;
  t.roll_rad = d.angle.x;
  t.pitch_rad = d.angle.y;
  t.yaw_rad = d.angle.z;
  t.p_radps = d.angrate.x;
  t.q_radps = d.angrate.y;
  t.r_radps = d.angrate.z;
  t.lat_deg = d.lla.x;
  t.lon_deg = d.lla.y;
  t.alt_m = d.lla.z;
  t.v_north_mps = d.velocity.x;
  t.v_east_mps = d.velocity.y;
  t.v_down_mps = d.velocity.z;
  t.airspeed_ftps = d.air_velocity;
  t.computer_in_command = d.PICCIC == 1;
  t.throttle = t.computer_in_command ? d.autothrottle : d.Throttle;
  t.voltage_v = d.voltage;
  t.ins_link_up = d.v_usbstatus == 1;
  t.ha_link_up = d.a_usbstatus == 1;
  t.waypoint_index = d.waypoint_index;
  return t;
}

// Calls the controller's ~set_tunable off the link loop: a service call waits on another
// process, and the loop must keep the link and the telemetry going meanwhile. The core times a
// request out on its own clock; an answer arriving later is still passed on.
class TunableClient {
 public:
  explicit TunableClient(std::string service)
      : service_(std::move(service)), worker_([this] { run(); }) {}
  ~TunableClient() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    worker_.join();
  }
  void submit(const ParamSetRequest& r) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      requests_.push_back(r);
    }
    wake_.notify_all();
  }
  std::vector<std::pair<ParamSetRequest, ParamSetAnswer>> take_answers() {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<std::pair<ParamSetRequest, ParamSetAnswer>> out;
    out.swap(answers_);
    return out;
  }
  const std::string& service() const { return service_; }

 private:
  void run() {
    std::unique_lock<std::mutex> lock(mutex_);
    while (true) {
      wake_.wait(lock, [this] { return stop_ || !requests_.empty(); });
      if (stop_) return;
      const ParamSetRequest r = requests_.front();
      requests_.pop_front();
      lock.unlock();
      const ParamSetAnswer a = call(r);
      lock.lock();
      answers_.emplace_back(r, a);
    }
  }

  ParamSetAnswer call(const ParamSetRequest& r) const {
    drone_ros::SetTunable srv;
    srv.request.name = r.ros_name;
    srv.request.value = r.value;
    ParamSetAnswer a;
    if (!ros::service::call(service_, srv)) {
      // Not running (or just restarting): nobody can vouch for a new value, so none is claimed.
      a.reason = ros::service::exists(service_, false)
                     ? "the controller's " + service_ + " call failed"
                     : "controller not running (no " + service_ + ")";
      return a;
    }
    a.accepted = srv.response.accepted;
    a.value_in_force = srv.response.value_in_force;
    a.reason = srv.response.reason;
    return a;
  }

  const std::string service_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<ParamSetRequest> requests_;
  std::vector<std::pair<ParamSetRequest, ParamSetAnswer>> answers_;
  bool stop_ = false;
  std::thread worker_;  // last: starts once everything it uses exists
};

class Node {
 public:
  Node(ros::NodeHandle& nh, NodeConfig config, std::unique_ptr<Transport> link)
      : config_(std::move(config)),
        link_(std::move(link)),
        core_(config_.core, config_.params),
        tunables_(config_.controller_param_ns + "/set_tunable"),
        tlog_(kTlogFlushPeriodMs) {
    // Relative names: the aircraft's namespace, so two aircraft on one master keep apart.
    way_pub_ = nh.advertise<drone_ros::way>("way", 1, true);  // latched: a late controller gets it
    command_pub_ = nh.advertise<drone_ros::OperatorCommand>("operator_command", 10);
    data_sub_ = nh.subscribe("data", 10, &Node::on_data, this);
    decision_sub_ = nh.subscribe("decision_status", 10, &Node::on_decision, this);
    home_sub_ = nh.subscribe("home", 1, &Node::on_home, this);  // latched by the `arduino` node
    updater_.setHardwareID(link_->describe());
    updater_.add("link", this, &Node::diagnose);
    if (!config_.tlog_path.empty() && tlog_.open(config_.tlog_path, now_clock().mono_ms)) {
      ROS_INFO("microhard_gs: MAVLink telemetry log (both directions) in %s",
               config_.tlog_path.c_str());
    }
  }

  void run() {
    uint8_t buf[2048];
    while (ros::ok()) {
      link_->maintain(now_clock().mono_ms);
      report_link_change();
      // The receive is the loop's wait: 5 ms, well inside a 50 Hz telemetry period.
      long n = link_->receive(buf, sizeof buf, 5);
      for (int i = 0; i < 64 && n != 0;
           ++i) {  // drain, but keep ROS callbacks flowing under a flood
        if (n < 0) {
          ++link_errors_;
          break;
        }
        const Clock now = now_clock();
        core_.handle_bytes(buf, static_cast<size_t>(n), now);
        for (const auto& frame : core_.take_received_frames()) {
          tlog_.add(now.unix_us, TlogDirection::kReceived, frame.data(), frame.size());
        }
        n = link_->receive(buf, sizeof buf, 0);
      }
      ros::spinOnce();
      core_.tick(now_clock());
      flush();
      tlog_.flush_if_due(now_clock().mono_ms);
      report_tlog_failure();
      updater_.update();
    }
  }

 private:
  void on_data(const drone_ros::data::ConstPtr& msg) {
    core_.set_telemetry(to_telemetry(*msg), now_clock());
  }

  void on_home(const drone_ros::HomePosition::ConstPtr& msg) {
    GeoPoint h;
    h.lat_deg = msg->latitude;
    h.lon_deg = msg->longitude;
    h.alt_m = msg->altitude;
    if (!core_.set_home(h)) {
      ROS_WARN("microhard_gs: home %u dropped: not a valid position", msg->seq);
    }
  }

  void on_decision(const drone_ros::DecisionStatus::ConstPtr& msg) {
    DecisionInfo d;
    d.controller = msg->controller;
    d.reasons = msg->reasons;
    d.reasons_at_switch = msg->reasons_at_switch;
    d.altitude_agl_ft = msg->altitude_agl_ft;
    core_.set_decision(d);
  }

  // Logs each change of the link's state once: the modem missing at start, unplugged, back.
  void report_link_change() {
    const LinkHealth& h = link_->health();
    if (h.up == link_was_up_ && h.last_error == last_link_error_) return;
    if (h.up) {
      ROS_INFO("microhard_gs: %s up (open %llu, %llu outages so far)", link_->describe().c_str(),
               static_cast<unsigned long long>(h.opens),
               static_cast<unsigned long long>(h.outages));
    } else {
      ROS_WARN("microhard_gs: %s down: %s; retrying every %.2f s, telemetry not sent meanwhile",
               link_->describe().c_str(), h.last_error.c_str(), config_.reopen_period_s);
    }
    link_was_up_ = h.up;
    last_link_error_ = h.last_error;
  }

  // A tlog that cannot be written costs the log, never the link: said once, then in the
  // diagnostics.
  void report_tlog_failure() {
    if (tlog_error_reported_ || !tlog_.failed()) return;
    ROS_ERROR("microhard_gs: tlog stopped: %s; the ground link goes on without it",
              tlog_.error().c_str());
    tlog_error_reported_ = true;
  }

  void flush() {
    // Answers first, so their PARAM_VALUE goes out in this round.
    for (const ParamSetRequest& r : core_.take_param_set_requests()) tunables_.submit(r);
    for (const auto& answered : tunables_.take_answers()) {
      if (!answered.second.accepted) {
        ROS_WARN("microhard_gs: %s = %g refused: %s", answered.first.ros_name.c_str(),
                 answered.first.value, answered.second.reason.c_str());
      }
      core_.param_set_answered(answered.first, answered.second);
    }
    // With the link down the core still runs (mission timeouts, announcements); what it would
    // have sent is dropped and counted, as a radio out of range would lose it.
    const bool up = link_->health().up;
    const uint64_t sent_us = now_clock().unix_us;
    for (const auto& frame : core_.take_frames()) {
      if (!up) {
        ++frames_not_sent_link_down_;
      } else if (!link_->send(frame.data(), frame.size())) {
        ++send_failures_;
      } else {
        tlog_.add(sent_us, TlogDirection::kSent, frame.data(), frame.size());
      }
    }
    for (const WayPlan& plan : core_.take_way_plans()) {
      drone_ros::way w;
      for (int i = 0; i < plan.fp; ++i) {
        w.north[i] = plan.north_ft[i];
        w.east[i] = plan.east_ft[i];
        w.height[i] = plan.height_ft[i];
        w.velocity[i] = plan.velocity_ftps[i];
      }
      w.fp = plan.fp;
      way_pub_.publish(w);
      ROS_INFO("microhard_gs: flight plan of %d waypoints published on /way", plan.fp);
    }
    for (OperatorRequest r : core_.take_operator_requests()) {
      drone_ros::OperatorCommand c;
      c.stamp = ros::Time::now();
      c.command = static_cast<uint8_t>(r);
      c.request_id = ++request_id_;
      seal(&c);
      command_pub_.publish(c);
    }
    for (const HomeRequest& r : core_.take_home_requests()) {
      drone_ros::OperatorCommand c;
      c.stamp = ros::Time::now();
      c.command = drone_ros::OperatorCommand::SET_HOME;
      c.request_id = ++request_id_;
      c.use_current = r.use_current;
      c.latitude = r.position.lat_deg;
      c.longitude = r.position.lon_deg;
      c.altitude = r.position.alt_m;
      seal(&c);
      command_pub_.publish(c);
    }
  }

  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& s) {
    const Counters& c = core_.counters();
    const LinkHealth& h = link_->health();
    if (!h.up) {
      s.summary(diagnostic_msgs::DiagnosticStatus::ERROR, "ground link down: " + h.last_error);
    } else if (!core_.home_known()) {
      s.summary(diagnostic_msgs::DiagnosticStatus::WARN, "no home position yet");
    } else if (core_.params().size() == 0) {
      // Some thesis tunables are absent from today's controller (listed below, not a fault);
      // none at all means controller_param_ns points at the wrong node.
      s.summary(diagnostic_msgs::DiagnosticStatus::WARN, "no controller parameters found");
    } else {
      s.summary(diagnostic_msgs::DiagnosticStatus::OK, "ok");
    }
    s.add("link", link_->describe());
    s.add("link_up", h.up ? "true" : "false");
    s.add("link_opens", h.opens);
    s.add("link_outages", h.outages);
    s.add("link_open_failures", h.open_failures);
    s.add("link_down_s", h.up ? 0.0 : (now_clock().mono_ms - h.down_since_ms) / 1000.0);
    s.add("link_last_error", h.last_error);
    s.add("frames_not_sent_link_down", frames_not_sent_link_down_);
    s.add("signing", config_.core.signing ? "on" : "off");
    // What the node last heard on /decision_status ("none" before the first status).
    const DecisionInfo* decision = core_.decision();
    s.add("decision_controller", decision ? std::to_string(decision->controller) : "none");
    s.add("decision_altitude_agl_ft",
          decision ? std::to_string(decision->altitude_agl_ft) : std::string("none"));
    s.add("frames_ok", c.frames_ok);
    s.add("frames_bad_crc", c.frames_bad_crc);
    s.add("refused_unsigned", c.refused_unsigned);
    s.add("refused_bad_signature", c.refused_bad_signature);
    s.add("ignored_other_target", c.ignored_other_target);
    s.add("missions_accepted", c.missions_accepted);
    s.add("missions_rejected", c.missions_rejected);
    s.add("mission_request_retries", c.mission_request_retries);
    s.add("mission_uploads_timed_out", c.mission_uploads_timed_out);
    s.add("commands_accepted", c.commands_accepted);
    s.add("commands_refused", c.commands_refused);
    s.add("telemetry_sets_sent", c.telemetry_sets_sent);
    s.add("send_failures", send_failures_);
    s.add("link_errors", link_errors_);
    s.add("param_sets_accepted", c.param_sets_accepted);
    s.add("param_sets_refused", c.param_sets_refused);
    s.add("param_sets_timed_out", c.param_sets_timed_out);
    s.add("parameters_served", core_.params().size());
    std::string missing;
    for (const auto& m : config_.missing_params) missing += (missing.empty() ? "" : ",") + m;
    s.add("parameters_missing", missing);
    s.add("tlog", config_.tlog_path.empty() ? std::string("off") : config_.tlog_path);
    s.add("tlog_records", tlog_.records_written());
    s.add("tlog_records_lost", tlog_.records_lost());
    s.add("tlog_error", tlog_.error());
    if (tlog_.failed()) s.mergeSummary(diagnostic_msgs::DiagnosticStatus::WARN, "tlog stopped");
  }

  NodeConfig config_;
  std::unique_ptr<Transport> link_;
  GsCore core_;
  TunableClient tunables_;
  TlogWriter tlog_;
  bool tlog_error_reported_ = false;
  ros::Publisher way_pub_;
  ros::Publisher command_pub_;
  ros::Subscriber data_sub_;
  ros::Subscriber decision_sub_;
  ros::Subscriber home_sub_;
  diagnostic_updater::Updater updater_;
  // The HA ignores a repeat of the request it executed last (same id and command): a restarted
  // node starts from the clock (ms), not from 0, so its first request is not taken for its
  // predecessor's last.
  uint32_t request_id_ = static_cast<uint32_t>(now_clock().unix_us / 1000u);
  uint64_t send_failures_ = 0;
  uint64_t link_errors_ = 0;
  uint64_t frames_not_sent_link_down_ = 0;
  bool link_was_up_ = true;  // so that a port missing at start is logged
  std::string last_link_error_;
};

}  // namespace
}  // namespace microhard_gs

namespace {

// The node's life once its parameters are good: the link (a bad UDP bind is fatal; a modem
// missing at start is an outage the node reports and waits out), then the node until shutdown.
int run_node(ros::NodeHandle& nh, ros::NodeHandle&, microhard_gs::NodeConfig config) {
  if (!config.missing_params.empty()) {
    ROS_INFO("microhard_gs: %zu known tunables not on the server under %s; not served",
             config.missing_params.size(), config.controller_param_ns.c_str());
  }
  std::string error;
  std::unique_ptr<microhard_gs::Transport> link;
  if (config.transport == "udp") {
    link = microhard_gs::UdpTransport::open(config.udp, &error);
  } else {
    link = std::make_unique<microhard_gs::SerialTransport>(
        config.serial_port, config.serial_baud,
        static_cast<uint64_t>(std::llround(config.reopen_period_s * 1000.0)));
  }
  if (!link) {
    ROS_FATAL("microhard_gs: %s", error.c_str());
    return 2;
  }
  ROS_INFO("microhard_gs: system %u on %s, signing %s, %zu parameters", config.core.system_id,
           link->describe().c_str(), config.core.signing ? "on" : "off", config.params.size());
  microhard_gs::Node node(nh, std::move(config), std::move(link));
  node.run();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return drone_ros_common::node_main<microhard_gs::NodeConfig>(
      argc, argv, "microhard_gs", microhard_gs::read_node_config, run_node);
}
