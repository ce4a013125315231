/* What the HA tells the HP every period, built from the core's state in one place for every
 * board that speaks the link, through the firmware loop (firmware/ha_firmware.c).
 * decision_status is the core's outputs field for field; pwm carries the pilot's sticks (decoded
 * with the calibration the core flies them with in manual mode) and PICCIC from the core's decision
 * (0 exactly when the core gives the pilot the servos, which also needs a valid RC link); home is
 * the INS adapter's, offered so that the link repeats it only now and then (ha_link_offer_home).
 * C99, no heap, time passed in. */
#ifndef HA_LINK_REPORT_H
#define HA_LINK_REPORT_H

#include <stdint.h>

#include "../core/ha_core.h"
#include "../core/ha_ins.h"
#include "../generated/ha_config.h"
#include "ha_link.h"

#ifdef __cplusplus
extern "C" {
#endif

void ha_report_decision_status(const HaOutputs *out, HaRosTime stamp,
                               drone_ros_DecisionStatus *msg);

void ha_report_pwm(const HaAircraftConfig *cfg, const HaInputs *in, const HaOutputs *out,
                   HaRosTime stamp, drone_ros_pwm *msg);

/* seq 0 (nothing to send) until home is latched. */
void ha_report_home(const HaIns *ins, HaRosTime stamp, drone_ros_HomePosition *msg);

/* The period's reports: decision_status and pwm published, home offered. Nothing while the host
 * is not connected. */
void ha_link_report_period(HaLink *link, const HaAircraftConfig *cfg, const HaInputs *in,
                           const HaOutputs *out, const HaIns *ins, uint32_t now_us);

#ifdef __cplusplus
}
#endif

#endif /* HA_LINK_REPORT_H */
