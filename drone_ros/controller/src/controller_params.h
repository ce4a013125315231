// Every parameter controller_<aircraft> uses, read and validated here and nowhere else. The
// values come from aircraft/<name>/controller_param.yaml and limits.yaml; the node reads them
// from its private ROS namespace, the tests and the benchmark straight from the files, both
// through a ParamLookup so the checks are the same.
#ifndef CONTROLLER_PARAMS_H
#define CONTROLLER_PARAMS_H

#include <functional>
#include <string>

#include "gnc_binding.h"

namespace controller {

// Looks a numeric parameter up by its path ("dt", "limits/actuators/elevator_limit_deg");
// false if missing or not a number.
using ParamLookup = std::function<bool(const std::string &key, double *value)>;

struct ControllerParams {
  GncParams gnc{};
  double rate_hz = 0.0;           // 1 / dt
  double sensor_timeout_s = 0.0;
  double q_weight = 0.0;
  // start trims, until the pilot's RC trims are captured
  double throttle_trim = 0.0;
  double elevator_trim_rad = 0.0;
  double aileron_trim_rad = 0.0;
  double rudder_trim_rad = 0.0;
  bool home_cmd = false;
};

// Fills params; on any missing or out-of-range value returns false and names it in *error.
bool build_controller_params(const ParamLookup &lookup, ControllerParams *params, std::string *error);

}  // namespace controller

#endif
