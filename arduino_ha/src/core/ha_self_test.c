#include "ha_self_test.h"

#include "ha_num.h"

typedef struct {
  uint8_t actuator; /* HA_U_* */
  int8_t direction; /* surfaces: fraction of the limit; throttle: halves of the test maximum */
} HaSelfTestStep;

static const HaSelfTestStep kSteps[] = {
    {HA_U_ELEVATOR_DEG, 1}, {HA_U_ELEVATOR_DEG, -1}, {HA_U_ELEVATOR_DEG, 0}, {HA_U_AILERON_DEG, 1},
    {HA_U_AILERON_DEG, -1}, {HA_U_AILERON_DEG, 0},   {HA_U_RUDDER_DEG, 1},   {HA_U_RUDDER_DEG, -1},
    {HA_U_RUDDER_DEG, 0},   {HA_U_THROTTLE, 1},      {HA_U_THROTTLE, 2},     {HA_U_THROTTLE, 0},
};
#define HA_SELF_TEST_STEPS (sizeof kSteps / sizeof kSteps[0])

void ha_self_test_start(HaSelfTestState *st, uint32_t now_us) {
  st->active = 1u;
  st->step = 0u;
  st->step_started_us = now_us;
}

int ha_self_test_target(HaSelfTestState *st, const HaAircraftConfig *cfg, uint32_t now_us,
                        HaSurfaces *target) {
  HaSelfTestStep step;
  float d;
  if (st->active && ha_elapsed_us(now_us, st->step_started_us) >= cfg->self_test_step_us) {
    st->step += 1u;
    st->step_started_us = now_us;
  }
  if (!st->active || st->step >= HA_SELF_TEST_STEPS) {
    st->active = 0u;
    return 0;
  }
  step = kSteps[st->step];
  d = (float)step.direction;
  target->elevator_deg = step.actuator == HA_U_ELEVATOR_DEG ? d * cfg->elevator_limit_deg : 0.0f;
  target->aileron_deg = step.actuator == HA_U_AILERON_DEG ? d * cfg->aileron_limit_deg : 0.0f;
  target->rudder_deg = step.actuator == HA_U_RUDDER_DEG ? d * cfg->rudder_limit_deg : 0.0f;
  target->throttle = cfg->throttle_min;
  if (step.actuator == HA_U_THROTTLE) {
    target->throttle += 0.5f * d * (cfg->self_test_throttle_max - cfg->throttle_min);
  }
  return 1;
}
