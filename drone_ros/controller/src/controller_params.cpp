#include "controller_params.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "limits_ranges.h"
#include "tunables_table.h"

namespace controller {
namespace {

// The aircraft's tunables.yaml, the list microhard_gs serves too (generated, tunables_table.h).
const tunables::Tunable *find_tunable(const std::string &name) {
  for (const tunables::Tunable &t : tunables::kTunables) {
    if (name == t.name) {
      return &t;
    }
  }
  return nullptr;
}

// Collects the first failure so the operator sees which parameter is wrong.
class Reader {
 public:
  Reader(const ParamLookup &lookup, std::string *error) : lookup_(lookup), error_(error) {}

  double get(const std::string &key, double lo, double hi, const char *units = nullptr) {
    double v = 0.0;
    if (!ok_) {
      return 0.0;
    }
    if (!lookup_(key, &v)) {
      fail(key + " is missing or not a number");
    } else if (!std::isfinite(v) || v < lo || v > hi) {
      std::ostringstream s;
      s << key << " = " << v << " is outside [" << lo << ", " << hi << "]";
      if (units != nullptr && std::string(units) != "1") {
        s << " " << units;
      }
      fail(s.str());
    }
    return v;
  }

  // A tunable, in its range of tunables.yaml, narrowed by [lo, hi] where another value bounds it.
  double get_tunable(const std::string &key, double lo = -HUGE_VAL, double hi = HUGE_VAL) {
    const tunables::Tunable *t = find_tunable(key);
    if (t == nullptr) {
      fail(key + " has no range: not in tunables.yaml");
      return 0.0;
    }
    return get(key, std::max(t->min, lo), std::min(t->max, hi), t->units);
  }

  int32_t get_tunable_choice(const std::string &key) { return whole(key, get_tunable(key)); }

  // A limits.yaml key, in the range every component accepts (aircraft/limits_ranges.yaml).
  double get_limit(const limits_ranges::Range &range) {
    return get(std::string("limits/") + range.key, range.min, range.max);
  }

  int32_t get_choice(const std::string &key, int32_t max_choice) {
    return whole(key, get(key, 0.0, max_choice));
  }

  // An optional value: false when absent (the caller's default stands), else read as get().
  bool get_optional(const std::string &key, double lo, double hi, double *v) {
    double probe = 0.0;
    if (!ok_ || !lookup_(key, &probe)) {
      return false;
    }
    *v = get(key, lo, hi);
    return ok_;
  }

  void require(bool condition, const std::string &what) {
    if (ok_ && !condition) {
      fail(what);
    }
  }

  bool ok() const { return ok_; }

 private:
  // A switch or a selection: a value already in range must also be whole.
  int32_t whole(const std::string &key, double v) {
    if (ok_ && v != std::floor(v)) {
      fail(key + " must be an integer");
    }
    return static_cast<int32_t>(v);
  }

  void fail(const std::string &message) {
    ok_ = false;
    if (error_ != nullptr) {
      *error_ = message;
    }
  }

  const ParamLookup &lookup_;
  std::string *error_;
  bool ok_ = true;
};

constexpr double kPi = 3.14159265358979323846;

// The bank and pitch limits of limits.yaml, which bound the guidance's commands.
struct AttitudeLimits {
  double roll_deg = 0.0;
  double pitch_deg = 0.0;
};

// limits.yaml's values the GNC flies inside, as every component accepts them.
AttitudeLimits read_limits(Reader &r, GncParams &g) {
  g.elevator_limit_deg = r.get_limit(limits_ranges::kActuatorsElevatorLimitDeg);
  g.elevator_pull_limit_deg = r.get_limit(limits_ranges::kActuatorsElevatorPullLimitDeg);
  r.require(g.elevator_pull_limit_deg <= g.elevator_limit_deg,
            "limits: elevator_pull_limit_deg must not exceed elevator_limit_deg");
  g.aileron_limit_deg = r.get_limit(limits_ranges::kActuatorsAileronLimitDeg);
  g.rudder_limit_deg = r.get_limit(limits_ranges::kActuatorsRudderLimitDeg);
  g.throttle_min = r.get_limit(limits_ranges::kActuatorsThrottleMin);
  g.throttle_max = r.get_limit(limits_ranges::kActuatorsThrottleMax);
  r.require(g.throttle_min < g.throttle_max, "limits: throttle_min must be below throttle_max");
  g.stall_speed_ftps = r.get_limit(limits_ranges::kStateStallSpeedFtps);
  g.airborne_agl_ft = r.get_limit(limits_ranges::kStateAirborneAglFt);
  AttitudeLimits a;
  a.roll_deg = r.get_limit(limits_ranges::kStateRollLimitDeg);
  a.pitch_deg = r.get_limit(limits_ranges::kStatePitchLimitDeg);
  return a;
}

// The trims inside the actuator limits, the trim airspeed and the estimator's first guess.
void read_trims(Reader &r, ControllerParams &p) {
  GncParams &g = p.gnc;
  p.throttle_trim = r.get_tunable("throttle_trim", g.throttle_min, g.throttle_max);
  p.elevator_trim_rad = r.get_tunable("elevator_trim", -g.elevator_limit_deg * kPi / 180.0,
                                      g.elevator_limit_deg * kPi / 180.0);
  p.aileron_trim_rad = r.get_tunable("aileron_trim", -g.aileron_limit_deg * kPi / 180.0,
                                     g.aileron_limit_deg * kPi / 180.0);
  p.rudder_trim_rad = r.get_tunable("rudder_trim", -g.rudder_limit_deg * kPi / 180.0,
                                    g.rudder_limit_deg * kPi / 180.0);
  g.vt_trim_ftps = r.get_tunable("VTtrim");
  r.require(g.vt_trim_ftps > g.stall_speed_ftps, "VTtrim must be above limits' stall_speed_ftps");
  g.alpha0_rad = r.get_tunable("alpha");
  g.beta0_rad = r.get_tunable("beta");
}

// Guidance: the path, the altitude loop and the commands it may give the inner loops.
void read_guidance(Reader &r, ControllerParams &p, const AttitudeLimits &limits) {
  GncParams &g = p.gnc;
  g.guidance_selection = r.get_tunable_choice("guidance_selection");
  p.home_cmd = r.get_choice("hmcmd", 1) == 1;
  g.mpf_switch = r.get_tunable_choice("mpf_switch");
  g.mpf_radius_ft = r.get_tunable("mpf_radius");
  g.path_select = r.get_tunable_choice("path_select");
  g.max_allow_error_ft = r.get_tunable("max_allow_error");
  g.dist2b_ft = r.get_tunable("dist2b");
  g.kp_lon_rad_per_ft = r.get_tunable("KpLon");
  g.ki_lon_rad_per_ft_s = r.get_tunable("KiLon");
  g.max_bank_deg = r.get_tunable("max_bank_deg", -HUGE_VAL, limits.roll_deg);
  g.max_pitch_cmd_deg = r.get_tunable("max_pitch_cmd_deg", -HUGE_VAL, limits.pitch_deg);
  g.attitude_cmd_rate_deg_s = r.get_tunable("attitude_cmd_rate_deg_s");
  g.min_airspeed_cmd_ftps = r.get_tunable("min_airspeed_cmd_ftps");
  r.require(g.min_airspeed_cmd_ftps > g.stall_speed_ftps,
            "min_airspeed_cmd_ftps must be above limits' stall_speed_ftps");
  // The HA hands control back only above this speed: an HP commanded slower would be taken over
  // at its slowest and never given the servos back.
  const double handback_ftps =
      g.stall_speed_ftps * r.get_limit(limits_ranges::kStateHandbackStallMultiple);
  r.require(
      g.min_airspeed_cmd_ftps > handback_ftps,
      "min_airspeed_cmd_ftps must be above the HA's hand-back speed (limits' stall_speed_ftps "
      "x handback_stall_multiple)");
  g.stall_prevention_min_bank_deg = r.get("stall_prevention_min_bank_deg", 1.0, g.max_bank_deg);
}

// The estimator's thresholds, the design weight the gains were made with, the node's timeout.
void read_estimator_and_node(Reader &r, ControllerParams &p) {
  GncParams &g = p.gnc;
  g.airspeed_valid_min_ftps = r.get_tunable("airspeed_valid_min_ftps");
  r.require(g.airspeed_valid_min_ftps < g.stall_speed_ftps,
            "airspeed_valid_min_ftps must be below the stall speed, or flight has no air data");
  g.converged_sigma_deg = r.get_tunable("converged_sigma_deg");
  p.q_weight = r.get_tunable("Q_weight");
  r.require(p.q_weight == GNC_DESIGN_Q_WEIGHT,
            "Q_weight differs from the weight the checked-in gains were designed with: rerun "
            "drone_ros/gnc/design/design_gains.py aircraft/" GNC_AIRCRAFT_NAME);
  p.sensor_timeout_s = r.get_tunable("sensor_timeout_s");
  r.require(p.sensor_timeout_s >= 2.0 * g.dt_s, "sensor_timeout_s must cover at least two periods");
  // Stepping on the VN-200's packets needs a whole number of them per period (the VN-200's rates
  // divide 800 Hz; 800 is the most it sends).
  double vn200_rate_hz = 0.0;
  if (r.get_optional("vn200_rate_hz", 1.0, 800.0, &vn200_rate_hz)) {
    const double per_step = vn200_rate_hz * g.dt_s;
    r.require(per_step > 0.5 && std::fabs(per_step - std::round(per_step)) < 1e-6,
              "vn200_rate_hz x dt must be a whole number of packets a step (the controller steps "
              "on the VN-200's packets)");
    p.packets_per_step = static_cast<uint32_t>(std::lround(per_step));
  }
}

}  // namespace

bool build_controller_params(const ParamLookup &lookup, ControllerParams *params,
                             std::string *error, ParamValues *used) {
  if (params == nullptr) {
    return false;
  }
  ParamValues read;
  const ParamLookup recording = [&lookup, &read](const std::string &key, double *value) {
    if (!lookup(key, value)) {
      return false;
    }
    read[key] = *value;
    return true;
  };
  Reader r(recording, error);
  ControllerParams p;
  // The thesis ran at 20 Hz; the HA decides at up to 100 Hz, so the HP may not step faster, and
  // not slower than the HA either (below).
  p.gnc.dt_s = r.get_tunable("dt");
  p.rate_hz = p.gnc.dt_s > 0.0 ? 1.0 / p.gnc.dt_s : 0.0;
  const AttitudeLimits limits = read_limits(r, p.gnc);
  // The HA counts each of its periods without a new command as late and takes over after
  // decision.late_periods_tolerated of them in a row: a controller stepping slower than the HA
  // decides would be taken over at every hand-back and never fly.
  const double ha_rate_hz = r.get_limit(limits_ranges::kDecisionRateHz);
  std::ostringstream slower;
  slower << "dt = " << p.gnc.dt_s
         << " s is longer than the HA's period (limits' decision.rate_hz = " << ha_rate_hz
         << " Hz: " << 1.0 / ha_rate_hz
         << " s): the HA would find a period without a new command every time and never hand "
            "control to the HP";
  r.require(p.gnc.dt_s * ha_rate_hz <= 1.0 + 1e-9, slower.str());
  read_trims(r, p);
  read_guidance(r, p, limits);
  read_estimator_and_node(r, p);
  if (!r.ok()) {
    return false;
  }
  *params = p;
  if (used != nullptr) {
    *used = read;
  }
  return true;
}

namespace {

using tunables::Tunable;

TunableKind kind_of(tunables::Apply apply) {
  switch (apply) {
    case tunables::Apply::kLive:
      return TunableKind::kLive;
    case tunables::Apply::kGncRestart:
      return TunableKind::kGncRestart;
    case tunables::Apply::kFixed:
      return TunableKind::kFixed;
  }
  return TunableKind::kNone;
}

}  // namespace

TunableKind tunable_kind(const std::string &name) {
  const Tunable *t = find_tunable(name);
  return t == nullptr ? TunableKind::kNone : kind_of(t->apply);
}

TunableResult change_tunable(const ParamValues &in_force, const std::string &name, double value,
                             bool hp_in_command, ControllerParams *params, ParamValues *values) {
  TunableResult result;
  const auto current = in_force.find(name);
  if (current != in_force.end()) {
    result.value_in_force = current->second;
  }
  const Tunable *tunable = find_tunable(name);
  const TunableKind kind = tunable == nullptr ? TunableKind::kNone : kind_of(tunable->apply);
  if (kind == TunableKind::kNone || current == in_force.end()) {
    result.reason = name + " is not a tunable of controller_" GNC_AIRCRAFT_NAME;
    return result;
  }
  if (value == current->second) {  // a GCS repeating a set: nothing to change, nothing to restart
    result.accepted = true;
    return result;
  }
  if (kind == TunableKind::kFixed) {
    result.reason = tunable->fixed_reason;
    return result;
  }
  ParamValues next = in_force;
  next[name] = value;
  ControllerParams built;
  std::string error;
  const ParamLookup lookup = [&next](const std::string &key, double *v) {
    const auto it = next.find(key);
    if (it == next.end()) {
      return false;
    }
    *v = it->second;
    return true;
  };
  if (!build_controller_params(lookup, &built, &error)) {
    result.reason = error;
    return result;
  }
  if (kind == TunableKind::kGncRestart && hp_in_command) {
    result.reason = name + " re-initializes the GNC: select the HA first";
    return result;
  }
  result.accepted = true;
  result.changed = true;
  result.restart_gnc = kind == TunableKind::kGncRestart;
  result.value_in_force = value;
  *params = built;
  *values = next;
  return result;
}

}  // namespace controller
