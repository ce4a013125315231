// What the ground station's core and its services share: the caller's clock, the vehicle's state
// (read-only to the services), the counters the node reports as diagnostics, and the parameter
// set requests the node carries to the controller.
#pragma once

#include <cstdint>
#include <string>

#include "geo.h"
#include "modes.h"

namespace microhard_gs {

struct Clock {
  uint64_t mono_ms = 0;  // monotonic: schedules and timeouts
  uint64_t unix_us = 0;  // wall clock: only for MAVLink 2 signing timestamps
};

// What the controller reported last on /data, in the units of the `data` message.
struct Telemetry {
  double roll_rad = 0, pitch_rad = 0, yaw_rad = 0;
  double p_radps = 0, q_radps = 0, r_radps = 0;
  double lat_deg = 0, lon_deg = 0, alt_m = 0;
  double v_north_mps = 0, v_east_mps = 0, v_down_mps = 0;
  double airspeed_ftps = 0;
  double throttle = 0;  // [0..1]
  double voltage_v = 0;
  bool ins_link_up = false;
  bool ha_link_up = false;
  bool computer_in_command = false;
  int32_t waypoint_index = 0;
};

struct DecisionInfo {
  uint8_t controller = kControllerHp;  // one of kController*
  uint32_t reasons = 0;
  uint32_t reasons_at_switch = 0;
  double altitude_agl_ft = 0.0;
};

// What the ground station knows of the vehicle, from the node (set_telemetry, set_home,
// set_decision on GsCore): the services read it, GsCore alone writes it.
struct VehicleState {
  bool have_telemetry = false;
  uint64_t telemetry_ms = 0;  // when the last telemetry came (Clock::mono_ms)
  Telemetry telemetry;
  bool have_decision = false;
  DecisionInfo decision;
  // Home from its one owner, the HA (/home).
  bool home_known = false;
  GeoPoint home;
};

// What the operator asked for last, as the CURRENT_MODE message reports it: the command service
// writes it, the telemetry reads it.
struct OperatorIntent {
  uint32_t custom_mode = 0;  // the last DO_SET_MODE's (0: none yet)
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
