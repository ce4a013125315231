// The command microservice: COMMAND_LONG/INT to operator requests, and their COMMAND_ACKs.
#include "gs_core.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "gs_core_emit.h"

namespace microhard_gs {

void GsCore::send_command_ack(const mavlink_message_t& msg, uint16_t command, uint8_t result) {
  mavlink_command_ack_t a{};
  a.command = command;
  a.result = result;
  a.target_system = msg.sysid;
  a.target_component = msg.compid;
  emit([&](mavlink_message_t* m) {
    mavlink_msg_command_ack_encode_status(config_.system_id, config_.component_id, out_.status(), m,
                                          &a);
  });
}

void GsCore::on_command(const mavlink_message_t& msg, uint16_t command, const float params[7],
                        uint8_t target_sys, uint8_t target_comp) {
  if (!addressed_to_us(target_sys, target_comp)) return;
  const uint8_t result = execute_command(command, params);
  if (result == MAV_RESULT_ACCEPTED) {
    ++counters_.commands_accepted;
  } else {
    ++counters_.commands_refused;
  }
  send_command_ack(msg, command, result);
  // Answers that follow the ACK (the requested message itself).
  if (result == MAV_RESULT_ACCEPTED) {
    const bool want_version = command == MAV_CMD_REQUEST_AUTOPILOT_CAPABILITIES ||
                              (command == MAV_CMD_REQUEST_MESSAGE &&
                               params[0] == static_cast<float>(MAVLINK_MSG_ID_AUTOPILOT_VERSION));
    const bool want_home = command == MAV_CMD_GET_HOME_POSITION ||
                           (command == MAV_CMD_REQUEST_MESSAGE &&
                            params[0] == static_cast<float>(MAVLINK_MSG_ID_HOME_POSITION));
    if (want_version) send_autopilot_version();
    if (want_home) send_home_position();
    const bool request = command == MAV_CMD_REQUEST_MESSAGE;
    if (request && params[0] == static_cast<float>(MAVLINK_MSG_ID_CURRENT_MODE))
      send_current_mode();
    if (request && params[0] == static_cast<float>(MAVLINK_MSG_ID_AVAILABLE_MODES)) {
      const int index = static_cast<int>(params[1]);
      for (int i = index == 0 ? 1 : index; i <= (index == 0 ? kModeCount : index); ++i)
        send_available_mode(i);
    }
  }
}

// The MAV_CMDs this vehicle understands (documented in microhard_gs/README.md):
//   DO_SET_MODE, param1 with CUSTOM_MODE_ENABLED, param2 = 0 -> SELECT_HP, 1 -> SELECT_HA
//   PREFLIGHT_REBOOT_SHUTDOWN, param1 = 0 (the HA is never rebooted from the ground),
//     param2 = 1 (reboot the onboard computer) -> RESTART_HP
//   ACTUATOR_TEST -> SELF_TEST (the HA's whole surface self-test; refused while airborne)
//   REQUEST_MESSAGE (AUTOPILOT_VERSION, HOME_POSITION), REQUEST_AUTOPILOT_CAPABILITIES,
//   GET_HOME_POSITION
//   DO_SET_HOME -> SET_HOME (on the ground only; gs_home.cpp)
// ACCEPTED for an operator request means "forwarded to the HA": the HA's checks still decide.
uint8_t GsCore::execute_command(uint16_t command, const float params[7]) {
  switch (command) {
    case MAV_CMD_DO_SET_MODE: {
      if (!std::isfinite(params[0]) || !std::isfinite(params[1])) return MAV_RESULT_DENIED;
      const uint32_t flags = static_cast<uint32_t>(params[0]);
      if ((flags & MAV_MODE_FLAG_CUSTOM_MODE_ENABLED) == 0) return MAV_RESULT_DENIED;
      if (params[1] == 0.0f || params[1] == 1.0f) {
        operator_requests_.push_back(params[1] == 0.0f ? OperatorRequest::kSelectHp
                                                       : OperatorRequest::kSelectHa);
        intended_custom_mode_ = params[1] == 0.0f ? kControllerHp : kControllerHa;
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
      if (vehicle_.have_decision && vehicle_.decision.altitude_agl_ft > config_.airborne_agl_ft) {
        send_statustext(MAV_SEVERITY_WARNING, "Self-test refused: airborne");
        return MAV_RESULT_TEMPORARILY_REJECTED;
      }
      operator_requests_.push_back(OperatorRequest::kSelfTest);
      return MAV_RESULT_ACCEPTED;
    case MAV_CMD_DO_SET_HOME:
      return command_int_ ? set_home_command(params[0], command_int_x_ * 1e-7,
                                             command_int_y_ * 1e-7, params[6])
                          : set_home_command(params[0], params[4], params[5], params[6]);
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

}  // namespace microhard_gs
