// Every parameter controller_<aircraft> uses, read and validated here and nowhere else. The
// values come from aircraft/<name>/controller_param.yaml and limits.yaml; the node reads them
// from its private ROS namespace, the tests and the benchmark straight from the files, both
// through a ParamLookup so the checks are the same.
#ifndef CONTROLLER_PARAMS_H
#define CONTROLLER_PARAMS_H

#include <functional>
#include <map>
#include <string>

#include "gnc.h"
#include "gnc_aircraft.h"

namespace controller {

// Looks a numeric parameter up by its path ("dt", "limits/actuators/elevator_limit_deg");
// false if missing or not a number.
using ParamLookup = std::function<bool(const std::string &key, double *value)>;

struct ControllerParams {
  GncParams gnc{};
  double rate_hz = 0.0;  // 1 / dt
  double sensor_timeout_s = 0.0;
  double q_weight = 0.0;
  // start trims, until the pilot's RC trims are captured
  double throttle_trim = 0.0;
  double elevator_trim_rad = 0.0;
  double aileron_trim_rad = 0.0;
  double rudder_trim_rad = 0.0;
  bool home_cmd = false;
  // Real time: a step on every packets_per_step-th VN-200 packet (packet_pacer.h), from the
  // optional ~vn200_rate_hz (flight.launch gives the sensor's rate); 0 without it: on the timer.
  uint32_t packets_per_step = 0;
};

// The raw values a ControllerParams was built from, by key: the set in force.
using ParamValues = std::map<std::string, double>;

// Fills params; on any missing or out-of-range value returns false and names it in *error.
// With `used`, also records every value it read (the base a later change is checked against).
bool build_controller_params(const ParamLookup &lookup, ControllerParams *params,
                             std::string *error, ParamValues *used = nullptr);

// How a tunable can change while the controller runs (set from the ground: PARAM_SET ->
// microhard_gs -> ~set_tunable).
enum class TunableKind {
  kNone,   // not a tunable: limits.yaml (the aircraft's envelope), frame_id, hmcmd, unknown keys
  kFixed,  // read at start-up only (dt, Q_weight): refused with the reason
  kLive,   // used afresh every step (start trims, sensor_timeout_s): applied at once
  kGncRestart,  // taken by the GNC only when it initializes: applied by re-initializing it
};
TunableKind tunable_kind(const std::string &name);

struct TunableResult {
  bool accepted = false;
  bool changed = false;      // accepted and different from the value in force
  bool restart_gnc = false;  // the change needs the GNC re-initialized
  double value_in_force = 0.0;
  std::string reason;  // why refused
};

// Checks setting `name` to `value` against the set in force: the whole set is rebuilt with the
// change through build_controller_params, so a remote change meets exactly the checks a file
// value meets. A change the GNC takes only at initialize is refused while the HP is in command
// (`hp_in_command`): re-initializing restarts the estimator and the guidance, which would hand
// the aircraft to the HA mid-flight. On acceptance *params and *values are the new set; on
// refusal they are untouched and value_in_force is the old value.
TunableResult change_tunable(const ParamValues &in_force, const std::string &name, double value,
                             bool hp_in_command, ControllerParams *params, ParamValues *values);

}  // namespace controller

#endif
