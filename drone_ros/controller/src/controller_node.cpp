#include "controller_node.h"

#include <XmlRpcValue.h>

#include <cmath>
#include <functional>
#include <stdexcept>
#include <utility>

#include "command_builder.h"
#include "param_tree.h"

namespace controller {

bool load_params(const ros::NodeHandle &pnh, ControllerParams *params, ParamValues *values,
                 std::string *frame_id, std::string *error) {
  XmlRpc::XmlRpcValue all;  // left empty (no struct) if the namespace has nothing: all missing
  (void)pnh.getParam(pnh.getNamespace(), all);
  const ParamLookup lookup = [&all](const std::string &key, double *value) {
    return number_at(all, key, value);
  };
  if (!build_controller_params(lookup, params, error, values)) {
    return false;
  }
  if (!pnh.getParam("frame_id", *frame_id) || frame_id->empty()) {
    *error = "frame_id is missing or empty";
    return false;
  }
  return true;
}

ControllerNode::ControllerNode(ros::NodeHandle &nh, ros::NodeHandle &pnh,
                               const ControllerParams &params, const ParamValues &values,
                               const std::string &frame_id)
    : pnh_(pnh), params_(params), values_(values), frame_id_(frame_id), board_(params) {
  if (gnc_initialize(&params_.gnc) != 0) {
    throw std::runtime_error("the GNC refused its parameters");
  }
  // On its own clock only the newest sample matters (queue of 1). In lockstep every message a
  // step declares must reach a callback to be counted, so none may be pushed out of the queue.
  pnh_.param("lockstep", lockstep_, false);
  // In lockstep a step's last input runs the step in the thread that received it. Not on the
  // real clock: there a packet re-arms the fallback timer, which an inline callback may not do.
  ros::NodeHandle sub_nh(nh);
  if (lockstep_) sub_nh.setCallbackQueue(&inline_);
  subscribe_home_and_plan(sub_nh);
  subscribe_inputs(sub_nh);
  servo_pub_ = nh.advertise<drone_ros::ServoCommand>("servo_op", 10);
  data_pub_ = nh.advertise<drone_ros::data>("data", 10);
  hil_pub_ = nh.advertise<drone_ros::hil_data>("to_hil", 10);

  set_tunable_srv_ = pnh_.advertiseService("set_tunable", &ControllerNode::on_set_tunable, this);

  start_diagnostics();
  start_stepping(nh, sub_nh);
  ROS_INFO("controller_%s stepping at %.1f Hz%s", GNC_AIRCRAFT_NAME, params_.rate_hz,
           lockstep_ ? " on /hil/lockstep"
           : pacer_  ? " on the VN-200's packets"
                     : " on its timer");
}

void ControllerNode::subscribe_home_and_plan(ros::NodeHandle &nh) {
  // Every topic name is relative: resolved in the node's namespace, so each aircraft launched in
  // a namespace of its own (<group ns="uav1">) flies on its own sensors only.
  // Home has one owner, the HA, which latches it from its own INS; the `arduino` node keeps it
  // on the latched /home, so a controller started again (HP restart) has the same home at once.
  // In lockstep each one counts for the step that declares it, so none may be pushed out of the
  // queue (as for the sensors below).
  const uint32_t q = lockstep_ ? 100 : 1;
  subs_.push_back(nh.subscribe<drone_ros::HomePosition>(
      "home", q, [this](const drone_ros::HomePosition::ConstPtr &m) {
        if (!lockstep_) {
          take_home(*m);
          return;
        }
        held_home_.hold(*m);
        on_input(kInHome);
      }));
  subs_.push_back(nh.subscribe<drone_ros::way>("way", q, [this](const drone_ros::way::ConstPtr &m) {
    if (!lockstep_) {
      take_way(*m);
      return;
    }
    held_way_.hold(*m);
    on_input(kInWay);
  }));
}

void ControllerNode::take_home(const drone_ros::HomePosition &m) {
  if (board_.on_home(m.latitude, m.longitude, m.altitude)) {
    ROS_INFO("home %u from the HA: %.7f %.7f %.1f m", m.seq, m.latitude, m.longitude, m.altitude);
  } else {
    ROS_WARN("home %u dropped: position not finite or out of range", m.seq);
  }
}

void ControllerNode::take_way(const drone_ros::way &m) {
  if (board_.on_way(m)) {
    ROS_INFO("new flight plan: %d waypoints", m.fp);
  } else {
    ROS_WARN("flight plan dropped: fp out of range or a waypoint not finite");
  }
}

// A VN-200 topic: the board takes each message as it arrives, and it counts for the lockstep step
// that declared it.
template <typename Msg>
void ControllerNode::subscribe_sensor(ros::NodeHandle &nh, const std::string &topic, uint32_t q,
                                      bool (SensorBoard::*take)(const Msg &, double),
                                      LockstepInput input) {
  subs_.push_back(nh.subscribe<Msg>(topic, q, [this, take, input](const typename Msg::ConstPtr &m) {
    (board_.*take)(*m, now_s());
    on_input(input);
  }));
}

// The sensors and the HA's reports: each counts for the lockstep's step that declared it.
void ControllerNode::subscribe_inputs(ros::NodeHandle &nh) {
  const uint32_t q = lockstep_ ? 100 : 1;
  subs_.push_back(nh.subscribe<drone_ros::pwm>("pwm", q, [this](const drone_ros::pwm::ConstPtr &m) {
    board_.on_pwm(*m, now_s());
    if (m->usbstatus != 0) {
      on_input(kInPwm);  // the HA's report; the node's own link-down /pwm is nobody's step
    }
  }));
  subscribe_sensor<drone_ros::ins>(nh, "ins", q, &SensorBoard::on_ins, kInIns);
  subscribe_sensor<sensor_msgs::NavSatFix>(nh, "gps_position", q, &SensorBoard::on_gps_position,
                                           kInGpsPosition);
  subscribe_sensor<geometry_msgs::Twist>(nh, "gps_velocity", q, &SensorBoard::on_gps_velocity,
                                         kInGpsVelocity);
  subscribe_sensor<sensor_msgs::Imu>(nh, "imu_PQR_acceleration", q, &SensorBoard::on_imu, kInImu);
  subscribe_sensor<geometry_msgs::Point>(nh, "attitude", q, &SensorBoard::on_attitude, kInAttitude);
  subs_.push_back(nh.subscribe<sensor_msgs::FluidPressure>(
      "pressure", 1, [this](const sensor_msgs::FluidPressure::ConstPtr &m) {
        board_.on_pressure(m->fluid_pressure);
      }));
  subs_.push_back(nh.subscribe<sensor_msgs::BatteryState>(
      "battery_state", 1,
      [this](const sensor_msgs::BatteryState::ConstPtr &m) { board_.on_battery(m->voltage); }));
  subs_.push_back(
      nh.subscribe("decision_status", lockstep_ ? 100 : 10, &ControllerNode::on_decision, this));
}

void ControllerNode::start_diagnostics() {
  diag_.setHardwareID(std::string("controller_") + GNC_AIRCRAFT_NAME);
  diag_.add("performance controller", this, &ControllerNode::diagnose);
  servo_op_rate_hz_ = params_.rate_hz;
  servo_op_rate_ = std::make_unique<diagnostic_updater::FrequencyStatus>(
      diagnostic_updater::FrequencyStatusParam(&servo_op_rate_hz_, &servo_op_rate_hz_, 0.1, 3),
      "/servo_op rate");
  diag_.add(*servo_op_rate_);
}

// On /hil/lockstep's steps, or on its own timer.
void ControllerNode::start_stepping(ros::NodeHandle &nh, ros::NodeHandle &sub_nh) {
  if (lockstep_) {
    lockstep_sub_ = sub_nh.subscribe("hil/lockstep", 100, &ControllerNode::on_lockstep, this,
                                     ros::TransportHints().tcpNoDelay());
    // Wall time: a declared message that never comes (a defect) must not stop the flight.
    lockstep_wait_check_ = nh.createSteadyTimer(ros::WallDuration(kLockstepWaitS / 4.0),
                                                [this](const ros::SteadyTimerEvent &) {
                                                  std::lock_guard<std::mutex> lock(inline_.mutex());
                                                  on_lockstep_wait_check();
                                                });
  } else if (params_.packets_per_step > 0) {
    pacer_ = std::make_unique<PacketPacer>(params_.gnc.dt_s, params_.packets_per_step);
    // One shot, armed again by every step: it fires only when no packet has run one.
    timer_ = nh.createSteadyTimer(
        ros::WallDuration(PacketPacer::kFallbackPeriods * params_.gnc.dt_s),
        [this](const ros::SteadyTimerEvent &) { on_fallback(); }, true);
  } else {
    timer_ =
        nh.createSteadyTimer(ros::WallDuration(params_.gnc.dt_s), &ControllerNode::on_timer, this);
  }
}

ControllerNode::~ControllerNode() {
  inline_.close();  // no callback runs on what goes below
  gnc_terminate();
}

void ControllerNode::restart_gnc() {
  gnc_terminate();
  if (gnc_initialize(&params_.gnc) != 0) {
    ROS_ERROR("GNC restart refused its parameters");  // validated at start-up: cannot happen
  }
  ++restarts_;
  ROS_WARN("HP restart requested by the HA: GNC re-initialized (%u restarts)", restarts_);
}

bool ControllerNode::on_set_tunable(drone_ros::SetTunable::Request &req,
                                    drone_ros::SetTunable::Response &res) {
  // Lockstep: not between a step's callbacks. Released before the parameter server's calls
  // below, which have no deadline and would hold up the receive thread meanwhile.
  std::unique_lock<std::mutex> lock(inline_.mutex());
  ControllerParams next;
  ParamValues next_values;
  const TunableResult r =
      change_tunable(values_, req.name, req.value, hp_in_control_, &next, &next_values);
  if (r.accepted && r.restart_gnc) {
    gnc_terminate();
    if (gnc_initialize(&next.gnc) != 0) {
      // build_controller_params' ranges lie inside the GNC's own, so this is a defect; fly on
      // with the old set rather than with none.
      (void)gnc_initialize(&params_.gnc);
      res.accepted = false;
      res.value_in_force = values_.count(req.name) != 0 ? values_.at(req.name) : 0.0;
      res.reason = "the GNC refused the new set";
      ++tunables_refused_;
      ROS_ERROR("tunable %s = %g: %s", req.name.c_str(), req.value, res.reason.c_str());
      return true;
    }
  }
  res.accepted = r.accepted;
  res.value_in_force = r.value_in_force;
  res.reason = r.reason;
  if (!r.accepted) {
    ++tunables_refused_;
    ROS_WARN("tunable %s = %g refused: %s", req.name.c_str(), req.value, r.reason.c_str());
    return true;
  }
  if (!r.changed) {
    return true;
  }
  params_ = next;
  values_ = next_values;
  board_.apply_params(params_);
  ++tunables_changed_;
  lock.unlock();
  // The parameter server shows what is in force, so a later HP restart or a reader sees it, in
  // the type the file gave it: a switch or selection stays an int.
  XmlRpc::XmlRpcValue loaded;
  if (pnh_.getParam(req.name, loaded) && loaded.getType() == XmlRpc::XmlRpcValue::TypeInt) {
    pnh_.setParam(req.name, static_cast<int>(r.value_in_force));
  } else {
    pnh_.setParam(req.name, r.value_in_force);
  }
  ROS_INFO("tunable %s = %g in force%s", req.name.c_str(), r.value_in_force,
           r.restart_gnc ? " (GNC re-initialized)" : "");
  return true;
}

void ControllerNode::on_decision(const drone_ros::DecisionStatus::ConstPtr &msg) {
  // A rising edge of restart_requested is one restart; holding it high is not many.
  if (msg->restart_requested && !restart_requested_) {
    restart_gnc();
  }
  restart_requested_ = msg->restart_requested;
  hp_in_control_ = msg->controller == drone_ros::DecisionStatus::CONTROLLER_HP;
  on_input(kInDecisionStatus);
}

void ControllerNode::on_timer(const ros::SteadyTimerEvent &event) {
  // A step that starts more than one period after it was due means we fell behind.
  if ((event.current_real - event.current_expected).toSec() > params_.gnc.dt_s) {
    ++late_steps_;
  }
  step(now_s(), ros::Time::now());
}

void ControllerNode::step_paced(bool on_packet) {
  const double now = ros::SteadyTime::now().toSec();
  if (!on_packet) {
    ++fallback_steps_;
  }
  pacer_->stepped(now);
  step(now, ros::Time::now());
  // Started again, the one-shot counts its period (the fallback's) from now.
  timer_.stop();
  timer_.start();
}

void ControllerNode::on_fallback() {
  // A firing already on its way when a packet's step re-armed the timer is not a late packet.
  if (ros::SteadyTime::now().toSec() < pacer_->fallback_at_s() - 1e-4) {
    return;
  }
  step_paced(false);
}

// Lockstep: the simulator publishes one /hil/lockstep per simulation step and waits for this
// node's /servo_op before it goes on. The step runs once every message the simulator declares
// has been received here (LockstepGate), whichever connection brings it last.
void ControllerNode::on_lockstep(const drone_ros::LockstepStep::ConstPtr &msg) {
  gate_.declare({msg->ins, msg->attitude, msg->gps_position, msg->gps_velocity,
                 msg->imu_pqr_acceleration, msg->pwm, msg->decision_status, msg->home, msg->way});
  held_home_.declared(gate_.declared(kInHome));
  held_way_.declared(gate_.declared(kInWay));
  const int64_t dt_ns = static_cast<int64_t>(std::llround(params_.gnc.dt_s * 1e9));
  const int64_t index = static_cast<int64_t>(msg->clock.toNSec()) / dt_ns;
  if (index <= lockstep_index_) {
    return;
  }
  if (lockstep_index_ >= 0 && index > lockstep_index_ + 1) {
    ++late_steps_;  // the clock skipped a period of ours
  }
  if (lockstep_pending_) {
    // The simulator went on without this node's answer: the old step is overdue.
    ++lockstep_wait_timeouts_;
    run_lockstep_step();
  }
  if (lockstep_index_ < 0) {
    // Whatever arrived before the first step arrived at it, in whichever order it came.
    lockstep_step_s_ = msg->clock.toSec();
    board_.restamp_arrivals(lockstep_step_s_);
  }
  lockstep_index_ = index;
  lockstep_pending_ = true;
  lockstep_pending_stamp_ = msg->clock;
  if (gate_.complete()) {
    run_lockstep_step();
  } else {
    lockstep_pending_since_s_ = ros::SteadyTime::now().toSec();
  }
}

void ControllerNode::on_input(LockstepInput input) {
  if (!lockstep_) {
    if (pacer_ && pacer_->on_sensor(input, ros::SteadyTime::now().toSec())) {
      step_paced(true);
    }
    return;
  }
  gate_.received(input);
  if (lockstep_pending_ && gate_.complete()) {
    run_lockstep_step();
  }
}

void ControllerNode::on_lockstep_wait_check() {
  if (!lockstep_pending_ ||
      ros::SteadyTime::now().toSec() - lockstep_pending_since_s_ < kLockstepWaitS) {
    return;
  }
  ++lockstep_wait_timeouts_;
  ROS_WARN("lockstep: stepping at %.3f s without %s after %.1f s", lockstep_pending_stamp_.toSec(),
           gate_.missing().c_str(), kLockstepWaitS);
  run_lockstep_step();
}

void ControllerNode::run_lockstep_step() {
  lockstep_pending_ = false;
  const ros::Time stamp = lockstep_pending_stamp_;
  if (const drone_ros::HomePosition *home = held_home_.release(gate_.declared(kInHome))) {
    take_home(*home);
  }
  if (const drone_ros::way *way = held_way_.release(gate_.declared(kInWay))) {
    take_way(*way);
  }
  step(stamp.toSec(), stamp);
  lockstep_step_s_ = stamp.toSec();
}

void ControllerNode::step(double now, const ros::Time &stamp) {
  ++steps_;
  board_.fill_input(&in_);
  // The HA flies its own command until its decision says the HP's is applied: the GNC then
  // starts its attitude command from the attitude it is handed.
  in_.ha_in_control = hp_in_control_ ? 0 : 1;
  // The estimator starts from its first input: a controller (re)started in flight that stepped
  // before the pitot's first /pwm would take the whole ground speed for wind. Until every
  // sensor has been heard from, the command goes out invalid (estimator not converged, links
  // unhealthy) and the GNC waits.
  if (board_.all_seen()) {
    gnc_step(&in_, &out_);
  }
  unhealthy_mask_ = board_.unhealthy_links(now);
  const drone_ros::ServoCommand cmd =
      build_servo_command(seq_++, stamp, out_, unhealthy_mask_ == 0, params_.gnc.throttle_min);
  if (!cmd.estimator_converged || !cmd.sensor_links_healthy) {
    ++invalid_steps_;
  }
  servo_pub_.publish(cmd);
  servo_op_rate_->tick();

  drone_ros::data data;
  data.header.stamp = stamp;
  data.header.frame_id = frame_id_;
  fill_data(board_, out_, hp_in_control_, &data);
  data_pub_.publish(data);

  drone_ros::hil_data hil;
  hil.header.stamp = stamp;
  hil.header.frame_id = frame_id_;
  fill_hil(out_, &hil);
  hil.ins_stamp = board_.ins().header.stamp;
  hil_pub_.publish(hil);
  diag_.update();
}

void ControllerNode::diagnose(diagnostic_updater::DiagnosticStatusWrapper &stat) {
  std::string stale;
  for (uint32_t i = 0; i < kLinkCount; ++i) {
    if (unhealthy_mask_ & (1u << i)) {
      stale += std::string(stale.empty() ? "" : " ") + link_name(static_cast<Link>(i));
    }
  }
  if (!stale.empty()) {
    stat.summary(diagnostic_msgs::DiagnosticStatus::ERROR, "sensor links unhealthy: " + stale);
  } else if (!out_.command_valid) {
    stat.summary(diagnostic_msgs::DiagnosticStatus::WARN,
                 "command invalid (estimator not converged or no home)");
  } else {
    stat.summary(diagnostic_msgs::DiagnosticStatus::OK, "flying");
  }
  stat.add("rate_hz", params_.rate_hz);
  stat.add("seq", seq_);
  stat.add("steps", steps_);
  stat.add("late_steps", late_steps_);
  if (lockstep_) {
    stat.add("lockstep_wait_timeouts", lockstep_wait_timeouts_);
  }
  if (pacer_) {
    stat.add("vn200_packets_per_step", params_.packets_per_step);
    stat.add("fallback_steps", fallback_steps_);
  }
  stat.add("invalid_steps", invalid_steps_);
  stat.add("restarts", restarts_);
  stat.add("tunables_changed", tunables_changed_);
  stat.add("tunables_refused", tunables_refused_);
  stat.add("dropped_messages", board_.dropped_messages());
  stat.add("rejected_gnc_inputs", out_.rejected_inputs);
  stat.add("estimator_converged", static_cast<int>(out_.estimator_converged));
  stat.add("home_valid", board_.home_valid());
  if (board_.home_valid()) {  // the HA's home this controller flies /way from, to full precision
    const SensorBoard::Home h = board_.home();
    stat.addf("home_lat_deg", "%.9f", h.lat_deg);
    stat.addf("home_lon_deg", "%.9f", h.lon_deg);
    stat.addf("home_alt_m", "%.3f", h.alt_m);
  }
  stat.add("waypoint_index", out_.waypoint_index);
  stat.add("guidance_mode", out_.guidance_mode);
}

}  // namespace controller
