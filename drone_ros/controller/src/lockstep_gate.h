// HiL lockstep: when may the controller step? The simulator declares, with each step
// (drone_ros/LockstepStep), how many messages of each controller input it saw published since its
// previous step; the controller counts what it receives and steps once nothing declared is
// missing. Counts, not stamps: /attitude and /gps_velocity carry no header. No ROS calls.
#ifndef CONTROLLER_LOCKSTEP_GATE_H
#define CONTROLLER_LOCKSTEP_GATE_H

#include <array>
#include <cstdint>
#include <deque>
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
  kInHome,
  kInWay,
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
  // Everything the steps so far declared of this input.
  uint64_t declared(LockstepInput input) const { return declared_[input]; }

 private:
  std::array<uint64_t, kLockstepInputCount> declared_{};
  std::array<uint64_t, kLockstepInputCount> received_{};
  bool declared_once_ = false;
};

const char *lockstep_input_topic(LockstepInput input);

// A latched state input (home, the flight plan) in lockstep: held when it arrives and handed over
// at the step that declares it. Taken on arrival, a controller started again in flight would have
// home from its first step or its third, as the connections came up, and its estimator (which
// needs home to tell the aircraft is wing-borne) would converge a step earlier or later.
template <typename Msg>
class HeldInput {
 public:
  void hold(const Msg &msg) { held_.push_back(msg); }
  // After each declaration, with the input's declared total. At the first, what is held beyond it
  // went out before this controller's first step, and no step will declare it: the newest are
  // kept, as LockstepGate keeps its count.
  void declared(uint64_t total) {
    if (!declared_once_) {
      while (held_.size() > total) {
        held_.pop_front();
      }
      declared_once_ = true;
    }
  }
  // At a step whose declared inputs are all in: the newest message the declarations cover and
  // not yet handed over, or nullptr. State, not events: only the newest matters.
  const Msg *release(uint64_t total) {
    bool any = false;
    while (released_ < total && !held_.empty()) {
      latest_ = held_.front();
      held_.pop_front();
      ++released_;
      any = true;
    }
    return any ? &latest_ : nullptr;
  }

 private:
  std::deque<Msg> held_;
  Msg latest_{};
  uint64_t released_ = 0;
  bool declared_once_ = false;
};

}  // namespace controller

#endif
