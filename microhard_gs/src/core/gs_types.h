// What the ground station's core and its services share: the caller's clock, the counters the
// node reports as diagnostics, and the parameter set requests the node carries to the controller.
#pragma once

#include <cstdint>
#include <string>

namespace microhard_gs {

struct Clock {
  uint64_t mono_ms = 0;  // monotonic: schedules and timeouts
  uint64_t unix_us = 0;  // wall clock: only for MAVLink 2 signing timestamps
};

// A PARAM_SET for the controller to decide (the node calls its ~set_tunable), answered with
// param_set_answered().
struct ParamSetRequest {
  uint32_t id = 0;
  std::string ros_name;
  double value = 0.0;
};

struct ParamSetAnswer {
  bool accepted = false;
  double value_in_force = 0.0;  // meaningful when accepted
  std::string reason;           // why refused
};

struct Counters {
  uint64_t frames_ok = 0;
  uint64_t frames_bad_crc = 0;    // corrupt frames (CRC or length), dropped
  uint64_t refused_unsigned = 0;  // signing on: unsigned message that changes something
  uint64_t refused_bad_signature = 0;
  uint64_t ignored_other_target = 0;  // addressed to another system
  uint64_t missions_accepted = 0;
  uint64_t missions_rejected = 0;
  uint64_t mission_request_retries = 0;
  uint64_t mission_uploads_timed_out = 0;
  uint64_t commands_accepted = 0;
  uint64_t commands_refused = 0;
  uint64_t telemetry_sets_sent = 0;
  uint64_t param_sets_accepted = 0;
  uint64_t param_sets_refused = 0;  // by the controller, or because it did not answer
  uint64_t param_sets_timed_out = 0;
};

}  // namespace microhard_gs
