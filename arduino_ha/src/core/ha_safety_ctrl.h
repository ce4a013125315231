/* The HA safety controller: a cascaded PID autopilot that keeps the aircraft inside its region
 * with the HP gone. It runs every period whoever drives the servos, and its integrators track the
 * surfaces actually applied, so a takeover starts from where the servos are (bumpless). */
#ifndef HA_SAFETY_CTRL_H
#define HA_SAFETY_CTRL_H

#include "ha_checks.h"

/* in_control: out of the previous period is what went to the servos (applied). Otherwise the
 * integrators are set so that the output equals applied. out is inside S_u. */
void ha_safety_ctrl_step(HaSafetyCtrlState *st, const HaAircraftConfig *cfg, const HaStateView *s,
                         const HaSurfaces *applied, int in_control, float dt_s, HaSurfaces *out);

void ha_safety_ctrl_reset(HaSafetyCtrlState *st);

#endif /* HA_SAFETY_CTRL_H */
