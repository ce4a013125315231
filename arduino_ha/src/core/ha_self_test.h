/* Pre-flight surface self-test (the original firmware's auto_test): each surface to + and - its
 * limit and back, then throttle steps, as the generator's table (HaAircraftConfig.self_test_u)
 * lists them. The core starts it only on the ground and on command, and rate-limits what it
 * commands like any other source. */
#ifndef HA_SELF_TEST_H
#define HA_SELF_TEST_H

#include "ha_core.h"

void ha_self_test_start(HaSelfTestState *st, uint32_t now_us);

/* Writes this moment's target; returns 0 (and clears active) once the sequence is over. */
int ha_self_test_target(HaSelfTestState *st, const HaAircraftConfig *cfg, uint32_t now_us,
                        HaSurfaces *target);

#endif /* HA_SELF_TEST_H */
