#include "modes.h"

#include <cstring>

namespace microhard_gs {
namespace {

// By DO_SET_MODE from the ground: the others are the decision logic's.
bool selectable(uint8_t controller) {
  return controller == kControllerHp || controller == kControllerHa;
}

bool known(uint8_t controller) { return controller < kModeCount; }

}  // namespace

const char* controller_name(uint8_t controller) {
  return known(controller) ? kControllerNames[controller] : "UNKNOWN";
}

uint8_t heartbeat_base_mode(bool have_decision, uint8_t controller, bool airborne) {
  uint8_t base = MAV_MODE_FLAG_CUSTOM_MODE_ENABLED;
  if (have_decision) {
    switch (controller) {
      case kControllerHp:
        base |= MAV_MODE_FLAG_AUTO_ENABLED | MAV_MODE_FLAG_GUIDED_ENABLED |
                MAV_MODE_FLAG_STABILIZE_ENABLED;
        break;
      case kControllerHa:
      case kControllerRecovering:
      case kControllerHaLatched:
        base |= MAV_MODE_FLAG_STABILIZE_ENABLED;
        break;
      case kControllerManual:
        base |= MAV_MODE_FLAG_MANUAL_INPUT_ENABLED;
        break;
      default:
        break;
    }
  }
  if (airborne) base |= MAV_MODE_FLAG_SAFETY_ARMED;
  return base;
}

bool available_mode(int mode_index, mavlink_available_modes_t* out) {
  if (mode_index < 1 || mode_index > kModeCount) return false;
  const uint8_t controller = static_cast<uint8_t>(mode_index - 1);  // custom_mode
  mavlink_available_modes_t m{};
  m.number_modes = kModeCount;
  m.mode_index = static_cast<uint8_t>(mode_index);
  m.standard_mode = MAV_STANDARD_MODE_NON_STANDARD;  // none of them is a standard mode's behaviour
  m.custom_mode = controller;
  m.properties =
      selectable(controller) ? 0u : static_cast<uint32_t>(MAV_MODE_PROPERTY_NOT_USER_SELECTABLE);
  std::strncpy(m.mode_name, kControllerNames[controller], sizeof m.mode_name - 1);
  *out = m;
  return true;
}

mavlink_current_mode_t current_mode(bool have_decision, uint8_t controller,
                                    uint32_t intended_custom_mode) {
  mavlink_current_mode_t m{};
  m.standard_mode = MAV_STANDARD_MODE_NON_STANDARD;
  m.custom_mode = have_decision ? controller : kCustomModeUnknown;
  m.intended_custom_mode = intended_custom_mode;
  return m;
}

}  // namespace microhard_gs
