#include "params.h"

#include <cmath>
#include <cstring>

namespace microhard_gs {

const std::vector<ParamSpec>& controller_param_specs() {
  // Names longer than 16 characters get a short MAVLink id; the rest keep their ROS name so an
  // operator recognises them in QGroundControl.
  static const std::vector<ParamSpec> specs = {
      {"gamma_flag", "gamma_flag", true},
      {"LQRselection", "LQRselection", true},
      {"smoothing_switching_guidance", "SMOOTH_SW_GUID", true},
      {"smoothing_switching_servo", "SMOOTH_SW_SERVO", true},
      {"time_window_servo", "TWIN_SERVO", false},
      {"time_window_guidance", "TWIN_GUIDANCE", false},
      {"KpLon", "KpLon", false},
      {"KiLon", "KiLon", false},
      {"L_Lat", "L_Lat", false},
      {"L_Lon", "L_Lon", false},
      {"Ka_Lon", "Ka_Lon", false},
      {"dist2b", "dist2b", false},
      {"KpLat", "KpLat", false},
      {"SAS_switch", "SAS_switch", true},
      {"k_dtheta_delevator", "K_DTHETA_DELEV", false},
      {"k_dQ_delevator", "k_dQ_delevator", false},
      {"k_dP_daileron", "k_dP_daileron", false},
      {"k_dR_drudder", "k_dR_drudder", false},
      {"K_phi_de", "K_phi_de", false},
      {"correction_switch", "CORRECTION_SW", true},
      {"Saturation_switch", "SATURATION_SW", true},
      {"phi_cmd_switch", "phi_cmd_switch", true},
      {"Vcorrection_switch", "VCORRECTION_SW", true},
      {"K_speed", "K_speed", false},
      {"Vstall", "Vstall", false},
      {"K_acc_guidance", "K_acc_guidance", false},
      {"Acc_feedback_on", "Acc_feedback_on", true},
      {"throttle_trim", "throttle_trim", false},
      {"elevator_trim", "elevator_trim", false},
      {"aileron_trim", "aileron_trim", false},
      {"rudder_trim", "rudder_trim", false},
      {"mpf_radius", "mpf_radius", false},
      {"mpf_switch", "mpf_switch", true},
      {"path_select", "path_select", true},
      // Q_weight and dt are shown, and the controller refuses to change them while running.
      {"Q_weight", "Q_weight", false},
      {"max_allow_error", "max_allow_error", false},
      {"VTtrim", "VTtrim", false},
      {"guidance_selection", "GUIDANCE_SELECT", true},
      {"dt", "dt", false},
      // Added by today's controller_DG808.
      {"max_bank_deg", "max_bank_deg", false},
      {"max_pitch_cmd_deg", "MAX_PITCH_CMD", false},
      {"min_airspeed_cmd_ftps", "MIN_AIRSPD_CMD", false},
      {"airspeed_valid_min_ftps", "AIRSPD_VALID_MIN", false},
      {"converged_sigma_deg", "CONVERGED_SIGMA", false},
      {"sensor_timeout_s", "sensor_timeout_s", false},
  };
  return specs;
}

void ParamTable::add(const ParamSpec& spec, double value) {
  Entry e;
  e.mav_id = spec.mav_id;
  e.ros_name = spec.ros_name;
  e.is_integer = spec.is_integer;
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

int ParamTable::find_ros_name(const std::string& ros_name) const {
  for (size_t i = 0; i < entries_.size(); ++i) {
    if (entries_[i].ros_name == ros_name) return static_cast<int>(i);
  }
  return -1;
}

void ParamTable::store(size_t index, double value) {
  if (index >= entries_.size() || !std::isfinite(value)) return;
  Entry& e = entries_[index];
  e.value = e.is_integer ? std::round(value) : value;
}

}  // namespace microhard_gs
