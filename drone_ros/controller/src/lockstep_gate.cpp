#include "lockstep_gate.h"

namespace controller {

const char *lockstep_input_topic(LockstepInput input) {
  static const char *const kTopics[kLockstepInputCount] = {
      "/ins", "/attitude",        "/gps_position", "/gps_velocity", "/imu_PQR_acceleration",
      "/pwm", "/decision_status", "/home",         "/way"};
  return input < kLockstepInputCount ? kTopics[input] : "?";
}

void LockstepGate::declare(const LockstepCounts &delivered) {
  for (uint32_t i = 0; i < kLockstepInputCount; ++i) {
    declared_[i] += delivered[i];
    if (!declared_once_ && received_[i] > declared_[i]) {
      received_[i] = declared_[i];
    }
  }
  declared_once_ = true;
}

bool LockstepGate::complete() const {
  for (uint32_t i = 0; i < kLockstepInputCount; ++i) {
    // More than declared is fine: the arduino node also publishes /pwm on the wall clock while
    // the HA link is down, which no step declares.
    if (received_[i] < declared_[i]) {
      return false;
    }
  }
  return true;
}

std::string LockstepGate::missing() const {
  std::string out;
  for (uint32_t i = 0; i < kLockstepInputCount; ++i) {
    if (received_[i] < declared_[i]) {
      out += (out.empty() ? "" : ", ") +
             std::string(lockstep_input_topic(static_cast<LockstepInput>(i))) + " " +
             std::to_string(declared_[i] - received_[i]);
    }
  }
  return out;
}

}  // namespace controller
