// controller_<aircraft>: steps the aircraft's GNC on the VN-200's packets (packet_pacer.h; on a
// monotonic timer when the sensor's rate is not given) and publishes the HP command (/servo_op),
// the ground telemetry (/data) and the HiL record (/to_hil). Thin: the sensor bookkeeping is
// SensorBoard, the message building command_builder, the flying the GNC.
// With ~lockstep (a HiL flight whose simulator owns time) it steps instead each time the
// simulator's /hil/lockstep crosses a multiple of dt, once that step's declared inputs are in,
// and measures sensor ages on that clock.
#ifndef CONTROLLER_NODE_H
#define CONTROLLER_NODE_H

#include <diagnostic_updater/diagnostic_updater.h>
#include <diagnostic_updater/update_functions.h>
#include <drone_ros/DecisionStatus.h>
#include <drone_ros/HomePosition.h>
#include <drone_ros/LockstepStep.h>
#include <drone_ros/SetTunable.h>
#include <drone_ros/way.h>
#include <ros/ros.h>
#include <sensor_msgs/BatteryState.h>
#include <sensor_msgs/FluidPressure.h>

#include <memory>
#include <string>
#include <vector>

#include "controller_params.h"
#include "drone_ros_common/inline_queue.h"
#include "lockstep_gate.h"
#include "packet_pacer.h"
#include "sensor_board.h"

namespace controller {

// Reads and validates the node's private parameters (the one place); false with *error set.
// *values receives the raw values read, the base later tunable changes are checked against.
bool load_params(const ros::NodeHandle &pnh, ControllerParams *params, ParamValues *values,
                 std::string *frame_id, std::string *error);

class ControllerNode {
 public:
  ControllerNode(ros::NodeHandle &nh, ros::NodeHandle &pnh, const ControllerParams &params,
                 const ParamValues &values, const std::string &frame_id);
  ~ControllerNode();

 private:
  // The constructor's parts, in its order.
  void subscribe_home_and_plan(ros::NodeHandle &nh);
  void subscribe_inputs(ros::NodeHandle &nh);
  template <typename Msg>
  void subscribe_sensor(ros::NodeHandle &nh, const std::string &topic, uint32_t q,
                        bool (SensorBoard::*take)(const Msg &, double), LockstepInput input);
  void take_home(const drone_ros::HomePosition &m);
  void take_way(const drone_ros::way &m);
  void start_diagnostics();
  void start_stepping(ros::NodeHandle &nh, ros::NodeHandle &sub_nh);
  // Arrival times of sensor messages: the monotonic clock in flight; in lockstep the time of the
  // last step, so that when a message arrived in wall time between two steps changes nothing.
  double now_s() const { return lockstep_ ? lockstep_step_s_ : ros::SteadyTime::now().toSec(); }
  void on_timer(const ros::SteadyTimerEvent &event);
  // Real time on the VN-200's packets: a step now, on a packet or on the fallback timer.
  void step_paced(bool on_packet);
  void on_fallback();
  void on_lockstep(const drone_ros::LockstepStep::ConstPtr &msg);
  // A sensor message arrived (after the board took it): may complete a pending lockstep step.
  void on_input(LockstepInput input);
  void on_lockstep_wait_check();
  void run_lockstep_step();
  void step(double now, const ros::Time &stamp);
  void on_decision(const drone_ros::DecisionStatus::ConstPtr &msg);
  void restart_gnc();
  // ~set_tunable: one tunable changed while running (the ground station's PARAM_SET).
  bool on_set_tunable(drone_ros::SetTunable::Request &req, drone_ros::SetTunable::Response &res);
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper &stat);

  ros::NodeHandle pnh_;
  ControllerParams params_;
  ParamValues values_;  // the raw values of params_, by key
  std::string frame_id_;
  SensorBoard board_;
  // Lockstep: the subscriptions' callbacks run in roscpp's receive thread (inline_queue.h); the
  // node's other callbacks take inline_.mutex(). Before subs_: it outlives them.
  drone_ros_common::InlineQueue inline_;
  std::vector<ros::Subscriber> subs_;
  ros::Publisher servo_pub_, data_pub_, hil_pub_;
  ros::SteadyTimer timer_;
  std::unique_ptr<PacketPacer> pacer_;  // real time with ~vn200_rate_hz
  uint64_t fallback_steps_ = 0;         // steps the fallback ran: a packet late or lost
  bool lockstep_ = false;
  // Longer than any scheduling hiccup, well inside the simulator's wait for a command.
  static constexpr double kLockstepWaitS = 2.0;
  ros::Subscriber lockstep_sub_;
  LockstepGate gate_;
  HeldInput<drone_ros::HomePosition> held_home_;
  HeldInput<drone_ros::way> held_way_;
  // Periodic, not armed per step: an inline callback may not start or stop a timer.
  ros::SteadyTimer lockstep_wait_check_;
  bool lockstep_pending_ = false;          // a step is due, waiting for its inputs
  double lockstep_pending_since_s_ = 0.0;  // since when, on the monotonic clock
  ros::Time lockstep_pending_stamp_;
  int64_t lockstep_index_ = -1;   // the last period stepped: floor(clock / dt)
  double lockstep_step_s_ = 0.0;  // its clock time
  uint64_t lockstep_wait_timeouts_ = 0;
  ros::ServiceServer set_tunable_srv_;
  diagnostic_updater::Updater diag_;
  // The /servo_op stream's rate against rate_hz: a controller that falls behind shows in the
  // lab's runtime monitor before the HA's deadline check takes the servos.
  double servo_op_rate_hz_ = 0.0;
  std::unique_ptr<diagnostic_updater::FrequencyStatus> servo_op_rate_;
  GncInput in_{};
  GncOutput out_{};
  uint32_t seq_ = 0;
  uint64_t steps_ = 0;
  uint64_t late_steps_ = 0;
  uint64_t invalid_steps_ = 0;
  uint32_t restarts_ = 0;
  uint32_t tunables_changed_ = 0;
  uint32_t tunables_refused_ = 0;
  uint32_t unhealthy_mask_ = 0;
  bool restart_requested_ = false;
  bool hp_in_control_ = false;
};

}  // namespace controller

#endif
