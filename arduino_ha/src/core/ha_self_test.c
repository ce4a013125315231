#include "ha_self_test.h"

#include "ha_num.h"

void ha_self_test_start(HaSelfTestState *st, uint32_t now_us) {
  st->active = 1u;
  st->step = 0u;
  st->step_started_us = now_us;
}

int ha_self_test_target(HaSelfTestState *st, const HaAircraftConfig *cfg, uint32_t now_us,
                        HaSurfaces *target) {
  const float *u;
  if (st->active && ha_elapsed_us(now_us, st->step_started_us) >= cfg->self_test_step_us) {
    st->step += 1u;
    st->step_started_us = now_us;
  }
  if (!st->active || st->step >= HA_SELF_TEST_STEPS) {
    st->active = 0u;
    return 0;
  }
  u = cfg->self_test_u[st->step]; /* the generator's sequence, inside S_u */
  target->elevator_deg = u[HA_U_ELEVATOR_DEG];
  target->aileron_deg = u[HA_U_AILERON_DEG];
  target->rudder_deg = u[HA_U_RUDDER_DEG];
  target->throttle = u[HA_U_THROTTLE];
  return 1;
}
