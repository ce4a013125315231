#include "params.h"

#include <cmath>
#include <cstring>

namespace microhard_gs {

const std::vector<ParamSpec>& controller_param_specs() {
  // Names longer than 16 characters get a short MAVLink id; the rest keep their ROS name so an
  // operator recognises them in QGroundControl.
  static const std::vector<ParamSpec> specs = {
      {"gamma_flag", "gamma_flag", true, false},
      {"LQRselection", "LQRselection", true, false},
      {"smoothing_switching_guidance", "SMOOTH_SW_GUID", true, false},
      {"smoothing_switching_servo", "SMOOTH_SW_SERVO", true, false},
      {"time_window_servo", "TWIN_SERVO", false, false},
      {"time_window_guidance", "TWIN_GUIDANCE", false, false},
      {"KpLon", "KpLon", false, false},
      {"KiLon", "KiLon", false, false},
      {"L_Lat", "L_Lat", false, false},
      {"L_Lon", "L_Lon", false, false},
      {"Ka_Lon", "Ka_Lon", false, false},
      {"dist2b", "dist2b", false, false},
      {"KpLat", "KpLat", false, false},
      {"SAS_switch", "SAS_switch", true, false},
      {"k_dtheta_delevator", "K_DTHETA_DELEV", false, false},
      {"k_dQ_delevator", "k_dQ_delevator", false, false},
      {"k_dP_daileron", "k_dP_daileron", false, false},
      {"k_dR_drudder", "k_dR_drudder", false, false},
      {"K_phi_de", "K_phi_de", false, false},
      {"correction_switch", "CORRECTION_SW", true, false},
      {"Saturation_switch", "SATURATION_SW", true, false},
      {"phi_cmd_switch", "phi_cmd_switch", true, false},
      {"Vcorrection_switch", "VCORRECTION_SW", true, false},
      {"K_speed", "K_speed", false, false},
      {"Vstall", "Vstall", false, false},
      {"K_acc_guidance", "K_acc_guidance", false, false},
      {"Acc_feedback_on", "Acc_feedback_on", true, false},
      {"throttle_trim", "throttle_trim", false, false},
      {"elevator_trim", "elevator_trim", false, false},
      {"aileron_trim", "aileron_trim", false, false},
      {"rudder_trim", "rudder_trim", false, false},
      {"mpf_radius", "mpf_radius", false, false},
      {"mpf_switch", "mpf_switch", true, false},
      {"path_select", "path_select", true, false},
      // The LQR gains are generated offline for one Q weight and the controller refuses to start
      // when this differs from the weight its gains were made with: visible, never set remotely.
      {"Q_weight", "Q_weight", false, true},
      {"max_allow_error", "max_allow_error", false, false},
      {"VTtrim", "VTtrim", false, false},
      {"guidance_selection", "GUIDANCE_SELECT", true, false},
      {"dt", "dt", false, false},
      // Added by today's controller_DG808.
      {"max_bank_deg", "max_bank_deg", false, false},
      {"max_pitch_cmd_deg", "MAX_PITCH_CMD", false, false},
      {"min_airspeed_cmd_ftps", "MIN_AIRSPD_CMD", false, false},
      {"airspeed_valid_min_ftps", "AIRSPD_VALID_MIN", false, false},
      {"converged_sigma_deg", "CONVERGED_SIGMA", false, false},
      {"sensor_timeout_s", "sensor_timeout_s", false, false},
  };
  return specs;
}

void ParamTable::add(const ParamSpec& spec, double value) {
  Entry e;
  e.mav_id = spec.mav_id;
  e.ros_name = spec.ros_name;
  e.is_integer = spec.is_integer;
  e.read_only = spec.read_only;
  e.value = spec.is_integer ? std::round(value) : value;
  entries_.push_back(e);
}

int ParamTable::find(const char* id, size_t id_len) const {
  const size_t len = strnlen(id, id_len);
  for (size_t i = 0; i < entries_.size(); ++i) {
    if (entries_[i].mav_id.size() == len && std::memcmp(entries_[i].mav_id.data(), id, len) == 0) {
      return static_cast<int>(i);
    }
  }
  return -1;
}

bool ParamTable::set(size_t index, double value) {
  if (index >= entries_.size() || !std::isfinite(value)) return false;
  Entry& e = entries_[index];
  if (e.read_only) return false;
  if (e.is_integer) {
    if (value != std::round(value) || std::fabs(value) > 2147483647.0) return false;
  }
  e.value = value;
  return true;
}

}  // namespace microhard_gs
