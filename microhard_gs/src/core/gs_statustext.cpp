// STATUSTEXT: who flies and why, announced on every change, split in chunks when long.
#include "gs_core.h"

#include <algorithm>
#include <cstring>

namespace microhard_gs {

std::string reason_names(uint32_t reasons) {
  std::string out;
  for (uint32_t bit = 0; bit < 32; ++bit) {
    if ((reasons & (1u << bit)) == 0) continue;
    if (!out.empty()) out += ",";
    if (bit < kReasonBits && kReasonNames[bit] != nullptr) {
      out += kReasonNames[bit];
    } else {
      out += "BIT" + std::to_string(bit);
    }
  }
  return out;
}

std::string decision_announcement(const DecisionInfo* previous, const DecisionInfo& now,
                                  uint8_t* severity) {
  const uint32_t why = now.reasons_at_switch != 0 ? now.reasons_at_switch : now.reasons;
  const std::string reasons = why != 0 ? reason_names(why) : std::string();
  std::string reason;
  switch (now.controller) {
    case kControllerHp:  // the HA hands control back only once its command stayed valid long enough
      *severity = MAV_SEVERITY_NOTICE;
      reason = "HP command stable";
      break;
    case kControllerHa:
      *severity = MAV_SEVERITY_WARNING;
      reason = reasons.empty() ? "no reason reported" : reasons;
      break;
    case kControllerRecovering:  // the HA still flies, the HP's command is valid again and on
                                 // probation
      *severity = MAV_SEVERITY_NOTICE;
      reason = "HP command valid, watching its stability";
      break;
    case kControllerHaLatched:  // the HA for good: the HP was restarted as often as allowed
      *severity = MAV_SEVERITY_CRITICAL;
      reason = "restart cap reached" + (reasons.empty() ? std::string() : "; " + reasons);
      break;
    case kControllerManual:
      *severity = MAV_SEVERITY_NOTICE;
      reason = "pilot in command (PIC switch)";
      break;
    default:
      *severity = MAV_SEVERITY_WARNING;
      reason = reasons.empty() ? "no reason reported" : reasons;
      break;
  }
  if (previous != nullptr && previous->controller == kControllerManual &&
      now.controller != kControllerManual) {
    reason = "PIC switch to computer; " + reason;
  }
  if (previous == nullptr) {
    // The first status this node sees: at boot, or mid-flight after a respawn. Either way the
    // operator has not been told who flies, nor why.
    return std::string("Controller ") + controller_name(now.controller) +
           " (first report): " + reason;
  }
  return std::string("Controller ") + controller_name(previous->controller) + "->" +
         controller_name(now.controller) + ": " + reason;
}

void GsCore::set_decision(const DecisionInfo& d) {
  const bool changed = !vehicle_.have_decision || d.controller != vehicle_.decision.controller;
  if (changed) {
    uint8_t severity = MAV_SEVERITY_NOTICE;
    const std::string text =
        decision_announcement(vehicle_.have_decision ? &vehicle_.decision : nullptr, d, &severity);
    out_.statustext(severity, text);
  }
  vehicle_.decision = d;
  vehicle_.have_decision = true;
  if (changed) telemetry_.send_current_mode();  // the standard-modes protocol wants it at once
}

}  // namespace microhard_gs
