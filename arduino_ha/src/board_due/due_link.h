/* The HP link on the Due: the rosserial device end (src/link/ha_link.h) over the USB port chosen
 * by DUE_HP_LINK_PORT (due_config.h: the programming port at 250000 baud by default, or the native
 * port). Received HP commands and operator requests go straight into the core's inputs; each
 * period the decision and the RC/airspeed readings are published back. */
#ifndef DUE_LINK_H
#define DUE_LINK_H

#include <stdint.h>

#include "../core/ha_core.h"

/* outputs: the core's, read for its on-the-ground verdict when a SET_HOME arrives. */
void due_link_begin(HaInputs *inputs, const HaOutputs *outputs);

/* Every loop: feeds received bytes to the link and keeps its time sync going. */
void due_link_poll(uint32_t now_us);

/* Once per period, after ha_app_period(): DecisionStatus and pwm to the HP. */
void due_link_publish(const HaAircraftConfig *cfg, const HaInputs *inputs, const HaOutputs *out,
                      uint32_t now_us);

#endif /* DUE_LINK_H */
