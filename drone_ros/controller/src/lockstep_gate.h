// HiL lockstep: when may the controller step? The simulator declares, with each step
// (drone_ros/LockstepStep), how many messages of each controller input it saw published since its
// previous step; the controller counts what it receives and steps once nothing declared is
// missing. Counts, not stamps: /attitude and /gps_velocity carry no header. No ROS calls.
#ifndef CONTROLLER_LOCKSTEP_GATE_H
#define CONTROLLER_LOCKSTEP_GATE_H

#include <array>
#include <cstdint>
#include <string>

namespace controller {

// In the order of drone_ros/LockstepStep's fields.
enum LockstepInput : uint32_t {
  kInIns = 0,
  kInAttitude,
  kInGpsPosition,
  kInGpsVelocity,
  kInImu,
  kInPwm,
  kInDecisionStatus,
  kLockstepInputCount
};

using LockstepCounts = std::array<uint32_t, kLockstepInputCount>;

class LockstepGate {
 public:
  // One step's declaration: added to everything declared since this controller started. What
  // arrived before the first declaration counts only up to what that declaration holds: the
  // rest was published before this controller's first step (the arduino node's link-down /pwm
  // at start-up), and no step will declare it.
  void declare(const LockstepCounts &delivered);
  // One message of this input arrived (counted before any check of its content: a message the
  // board drops as not finite was still delivered).
  void received(LockstepInput input) { ++received_[input]; }
  // Every declared message has arrived.
  bool complete() const;
  // What is still missing, as "/ins 1, /pwm 2", for the warning when the wait runs out.
  std::string missing() const;

 private:
  std::array<uint64_t, kLockstepInputCount> declared_{};
  std::array<uint64_t, kLockstepInputCount> received_{};
  bool declared_once_ = false;
};

const char *lockstep_input_topic(LockstepInput input);

}  // namespace controller

#endif
