// The command microservice (gs_command_service.h).
#include <cmath>
#include <utility>

#include "gs_command_service.h"
#include "modes.h"

namespace microhard_gs {

void CommandService::ack(const mavlink_message_t& msg, uint16_t command, uint8_t result) {
  mavlink_command_ack_t a{};
  a.command = command;
  a.result = result;
  a.target_system = msg.sysid;
  a.target_component = msg.compid;
  out_.emit([&](mavlink_message_t* m) {
    mavlink_msg_command_ack_encode_status(out_.system_id(), out_.component_id(), out_.status(), m,
                                          &a);
  });
}

void CommandService::deny(const mavlink_message_t& msg, uint16_t command) {
  ack(msg, command, MAV_RESULT_DENIED);
}

void CommandService::on_command(const mavlink_message_t& msg, const CommandArgs& c) {
  const uint8_t result = execute(c);
  if (result == MAV_RESULT_ACCEPTED) {
    ++counters_.commands_accepted;
  } else {
    ++counters_.commands_refused;
  }
  ack(msg, c.command, result);
  if (result == MAV_RESULT_ACCEPTED) send_requested(c);
}

void CommandService::send_requested(const CommandArgs& c) {
  const float* params = c.params;
  const bool request = c.command == MAV_CMD_REQUEST_MESSAGE;
  const bool want_version =
      c.command == MAV_CMD_REQUEST_AUTOPILOT_CAPABILITIES ||
      (request && params[0] == static_cast<float>(MAVLINK_MSG_ID_AUTOPILOT_VERSION));
  const bool want_home = c.command == MAV_CMD_GET_HOME_POSITION ||
                         (request && params[0] == static_cast<float>(MAVLINK_MSG_ID_HOME_POSITION));
  if (want_version) telemetry_.send_autopilot_version();
  if (want_home) telemetry_.send_home_position();
  if (request && params[0] == static_cast<float>(MAVLINK_MSG_ID_CURRENT_MODE))
    telemetry_.send_current_mode();
  if (request && params[0] == static_cast<float>(MAVLINK_MSG_ID_AVAILABLE_MODES)) {
    const int index = static_cast<int>(params[1]);
    for (int i = index == 0 ? 1 : index; i <= (index == 0 ? kModeCount : index); ++i)
      telemetry_.send_available_mode(i);
  }
}

// The MAV_CMDs this vehicle understands (documented in microhard_gs/README.md):
//   DO_SET_MODE, param1 with CUSTOM_MODE_ENABLED, param2 = 0 -> SELECT_HP, 1 -> SELECT_HA
//   PREFLIGHT_REBOOT_SHUTDOWN, param1 = 0 (the HA is never rebooted from the ground),
//     param2 = 1 (reboot the onboard computer) -> RESTART_HP
//   ACTUATOR_TEST -> SELF_TEST (the HA's whole surface self-test; refused while airborne)
//   REQUEST_MESSAGE (AUTOPILOT_VERSION, HOME_POSITION), REQUEST_AUTOPILOT_CAPABILITIES,
//   GET_HOME_POSITION
//   DO_SET_HOME -> SET_HOME (on the ground only; set_home below)
// ACCEPTED for an operator request means "forwarded to the HA": the HA's checks still decide.
uint8_t CommandService::execute(const CommandArgs& c) {
  const float* params = c.params;
  const uint16_t command = c.command;
  switch (command) {
    case MAV_CMD_DO_SET_MODE: {
      if (!std::isfinite(params[0]) || !std::isfinite(params[1])) return MAV_RESULT_DENIED;
      const uint32_t flags = static_cast<uint32_t>(params[0]);
      if ((flags & MAV_MODE_FLAG_CUSTOM_MODE_ENABLED) == 0) return MAV_RESULT_DENIED;
      if (params[1] == 0.0f || params[1] == 1.0f) {
        operator_requests_.push_back(params[1] == 0.0f ? OperatorRequest::kSelectHp
                                                       : OperatorRequest::kSelectHa);
        intent_.custom_mode = params[1] == 0.0f ? kControllerHp : kControllerHa;
        return MAV_RESULT_ACCEPTED;
      }
      return MAV_RESULT_DENIED;
    }
    case MAV_CMD_PREFLIGHT_REBOOT_SHUTDOWN:
      if (params[0] == 0.0f && params[1] == 1.0f) {
        operator_requests_.push_back(OperatorRequest::kRestartHp);
        return MAV_RESULT_ACCEPTED;
      }
      return MAV_RESULT_DENIED;
    case MAV_CMD_ACTUATOR_TEST:
      // The HA refuses it in the air too; refusing here first gives the operator the reason.
      if (vehicle_.have_decision && vehicle_.decision.altitude_agl_ft > airborne_agl_ft_) {
        out_.statustext(MAV_SEVERITY_WARNING, "Self-test refused: airborne");
        return MAV_RESULT_TEMPORARILY_REJECTED;
      }
      operator_requests_.push_back(OperatorRequest::kSelfTest);
      return MAV_RESULT_ACCEPTED;
    case MAV_CMD_DO_SET_HOME:
      return c.is_int ? set_home(params[0], c.x_e7 * 1e-7, c.y_e7 * 1e-7, params[6])
                      : set_home(params[0], params[4], params[5], params[6]);
    case MAV_CMD_REQUEST_AUTOPILOT_CAPABILITIES:
    case MAV_CMD_GET_HOME_POSITION:
      if (command == MAV_CMD_GET_HOME_POSITION && !vehicle_.home_known)
        return MAV_RESULT_TEMPORARILY_REJECTED;
      return MAV_RESULT_ACCEPTED;
    case MAV_CMD_REQUEST_MESSAGE:
      if (params[0] == static_cast<float>(MAVLINK_MSG_ID_AUTOPILOT_VERSION))
        return MAV_RESULT_ACCEPTED;
      if (params[0] == static_cast<float>(MAVLINK_MSG_ID_HOME_POSITION)) {
        return vehicle_.home_known ? MAV_RESULT_ACCEPTED : MAV_RESULT_TEMPORARILY_REJECTED;
      }
      if (params[0] == static_cast<float>(MAVLINK_MSG_ID_CURRENT_MODE)) return MAV_RESULT_ACCEPTED;
      if (params[0] == static_cast<float>(MAVLINK_MSG_ID_AVAILABLE_MODES)) {
        // param2: 0 for every mode, else the index of one (1-based).
        const bool one = params[1] >= 1.0f && params[1] <= static_cast<float>(kModeCount) &&
                         params[1] == std::floor(params[1]);
        return params[1] == 0.0f || one ? MAV_RESULT_ACCEPTED : MAV_RESULT_DENIED;
      }
      return MAV_RESULT_UNSUPPORTED;
    default:
      return MAV_RESULT_UNSUPPORTED;
  }
}

// MAV_CMD_DO_SET_HOME: param1 1 = here (where the HA's INS says the aircraft is), 0 = the
// position in params 5-7 (altitude: WGS84 ellipsoid height, as HOME_POSITION reports it). Only on
// the ground: moving the origin of /way, of the HA's circle and of its ceiling in flight would
// shift all three under the aircraft. The HA refuses it in the air too (ha_ins_set_home), and
// decides: ACCEPTED means forwarded, the new home comes back on /home as HOME_POSITION.
uint8_t CommandService::set_home(float use_current, double lat_deg, double lon_deg, float alt_m) {
  if (!vehicle_.have_decision) {
    out_.statustext(MAV_SEVERITY_WARNING,
                    "Set home refused: no HA status, cannot tell it is on the ground");
    return MAV_RESULT_TEMPORARILY_REJECTED;
  }
  if (vehicle_.decision.altitude_agl_ft > airborne_agl_ft_) {
    out_.statustext(MAV_SEVERITY_WARNING, "Set home refused: in flight");
    return MAV_RESULT_TEMPORARILY_REJECTED;
  }
  HomeRequest r;
  r.use_current = use_current == 1.0f;
  if (!r.use_current) {
    if (use_current != 0.0f || !is_valid_home(GeoPoint{lat_deg, lon_deg, alt_m})) {
      out_.statustext(MAV_SEVERITY_WARNING, "Set home refused: not a valid position");
      return MAV_RESULT_DENIED;
    }
    r.position.lat_deg = lat_deg;
    r.position.lon_deg = lon_deg;
    r.position.alt_m = alt_m;
  }
  home_requests_.push_back(r);
  return MAV_RESULT_ACCEPTED;
}

std::vector<OperatorRequest> CommandService::take_operator_requests() {
  return std::exchange(operator_requests_, {});
}

std::vector<HomeRequest> CommandService::take_home_requests() {
  return std::exchange(home_requests_, {});
}

}  // namespace microhard_gs
