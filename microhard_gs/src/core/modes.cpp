#include "modes.h"

#include <cstring>

namespace microhard_gs {
namespace {

struct ModeSpec {
  uint8_t controller;
  const char* name;
  bool selectable;  // by DO_SET_MODE from the ground
};

// Indexed by controller number (= custom_mode).
constexpr ModeSpec kModes[kModeCount] = {
    {kControllerHp, "HP", true},
    {kControllerHa, "HA", true},
    {kControllerRecovering, "RECOVERING", false},
    {kControllerHaLatched, "HA_LATCHED", false},
    {kControllerManual, "MANUAL", false},
};

bool known(uint8_t controller) { return controller < kModeCount; }

}  // namespace

const char* controller_name(uint8_t controller) {
  return known(controller) ? kModes[controller].name : "UNKNOWN";
}

uint8_t heartbeat_base_mode(bool have_decision, uint8_t controller, bool airborne) {
  uint8_t base = MAV_MODE_FLAG_CUSTOM_MODE_ENABLED;
  if (have_decision) {
    switch (controller) {
      case kControllerHp:
        base |= MAV_MODE_FLAG_AUTO_ENABLED | MAV_MODE_FLAG_GUIDED_ENABLED | MAV_MODE_FLAG_STABILIZE_ENABLED;
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
  const ModeSpec& spec = kModes[mode_index - 1];
  mavlink_available_modes_t m{};
  m.number_modes = kModeCount;
  m.mode_index = static_cast<uint8_t>(mode_index);
  m.standard_mode = MAV_STANDARD_MODE_NON_STANDARD;  // none of them is a standard mode's behaviour
  m.custom_mode = spec.controller;
  m.properties = spec.selectable ? 0u : static_cast<uint32_t>(MAV_MODE_PROPERTY_NOT_USER_SELECTABLE);
  std::strncpy(m.mode_name, spec.name, sizeof m.mode_name - 1);
  *out = m;
  return true;
}

mavlink_current_mode_t current_mode(bool have_decision, uint8_t controller, uint32_t intended_custom_mode) {
  mavlink_current_mode_t m{};
  m.standard_mode = MAV_STANDARD_MODE_NON_STANDARD;
  m.custom_mode = have_decision ? controller : kCustomModeUnknown;
  m.intended_custom_mode = intended_custom_mode;
  return m;
}

}  // namespace microhard_gs
