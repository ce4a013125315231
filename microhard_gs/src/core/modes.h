// The flight modes a ground station can name: who flies (DecisionStatus.CONTROLLER_*) is the
// HEARTBEAT's custom_mode, and the MAVLink standard-modes messages (AVAILABLE_MODES,
// CURRENT_MODE) give each one its name. No I/O, no time.
#pragma once

#include <cstdint>

#include "decision_status_names.h"
#include "mavlink_all.h"

namespace microhard_gs {

// Who flies, as DecisionStatus.CONTROLLER_* numbers it (kController*, generated from the message:
// this core is ROS-free). These are the custom_mode values.
constexpr int kModeCount = kControllerCount;
// custom_mode before the first DecisionStatus: no mode of the list.
constexpr uint32_t kCustomModeUnknown = 0xFFFFFFFFu;

// "HP", "HA", "RECOVERING", "HA_LATCHED", "MANUAL"; "UNKNOWN" for anything else. The names the
// STATUSTEXT announcements and AVAILABLE_MODES both use.
const char* controller_name(uint8_t controller);

// HEARTBEAT base_mode for who flies, consistent with its custom_mode: CUSTOM_MODE_ENABLED always;
// the HP flies the mission (AUTO, GUIDED, STABILIZE), the HA's safety controller stabilizes
// (HA, RECOVERING, HA_LATCHED: STABILIZE), the pilot flies MANUAL (MANUAL_INPUT); SAFETY_ARMED
// while airborne.
uint8_t heartbeat_base_mode(bool have_decision, uint8_t controller, bool airborne);

// AVAILABLE_MODES for mode_index 1..kModeCount (false outside). Only HP and HA can be selected
// (DO_SET_MODE); the others are the decision logic's and are marked NOT_USER_SELECTABLE.
bool available_mode(int mode_index, mavlink_available_modes_t* out);

// CURRENT_MODE: who flies, and the operator's last selection (0 = none, as the message defines
// it; selecting the HP, custom_mode 0, therefore reads as "none").
mavlink_current_mode_t current_mode(bool have_decision, uint8_t controller,
                                    uint32_t intended_custom_mode);

}  // namespace microhard_gs
