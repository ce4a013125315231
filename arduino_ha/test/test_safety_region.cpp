// The safety regions S_x x <= 1 and S_u u <= 1 as generated from limits.yaml.
#include <gtest/gtest.h>

#include <cmath>

#include "ha_aircraft.h"
#include "ha_core.h"

extern "C" {
#include "ha_region.h"
}

namespace {

const HaAircraftConfig& cfg = ha_aircraft_config;

TEST(HaSafetyRegion, LevelFlightIsWellInside) {
  float x[HA_X_DIM] = {4.0f, 0.0f, 0.0f, 2.0f, 0.0f, 0.0f, 0.0f, 200.0f};
  EXPECT_LE(ha_state_region_max(&cfg, x), cfg.inner_region_fraction);
}

TEST(HaSafetyRegion, EachStateLimitIsTheBoundary) {
  const float limits[HA_X_DIM] = {cfg.alpha_limit_deg, cfg.beta_limit_deg, 0, 0, 0, 0, 0,
                                  cfg.ceiling_agl_ft};
  for (int j : {HA_X_ALPHA_DEG, HA_X_BETA_DEG, HA_X_ALT_AGL_FT}) {
    float x[HA_X_DIM] = {};
    x[j] = limits[j] * 0.99f;
    EXPECT_LT(ha_state_region_max(&cfg, x), 1.0f) << j;
    x[j] = limits[j] * 1.01f;
    EXPECT_GT(ha_state_region_max(&cfg, x), 1.0f) << j;
    if (j != HA_X_ALT_AGL_FT) {  // angles are symmetric; altitude has only the ceiling
      x[j] = -limits[j] * 1.01f;
      EXPECT_GT(ha_state_region_max(&cfg, x), 1.0f) << j;
    }
  }
}

TEST(HaSafetyRegion, ActuatorLimitsAreTheBoundary) {
  float u[HA_U_DIM] = {cfg.elevator_limit_deg, -cfg.aileron_limit_deg, cfg.rudder_limit_deg,
                       cfg.throttle_max};
  EXPECT_LE(ha_actuator_region_max(&cfg, u), 1.0f + 1e-6f);
  u[HA_U_AILERON_DEG] = -cfg.aileron_limit_deg - 0.1f;
  EXPECT_GT(ha_actuator_region_max(&cfg, u), 1.0f);
  u[HA_U_AILERON_DEG] = 0.0f;
  u[HA_U_THROTTLE] = cfg.throttle_min - 0.01f;
  EXPECT_GT(ha_actuator_region_max(&cfg, u), 1.0f);
}

TEST(HaSafetyRegion, HugeValuesAreOutsideNotOverflowed) {
  float u[HA_U_DIM] = {3e38f, -3e38f, 3e38f, -3e38f};
  const float m = ha_actuator_region_max(&cfg, u);
  EXPECT_TRUE(std::isfinite(m));
  EXPECT_GT(m, 1.0f);
}

}  // namespace

namespace {

TEST(HaServoPulses, LimitsMapToTheConfiguredPulseRangeAndNanToNeutral) {
  uint16_t pulses[HA_U_DIM];
  HaSurfaces s{cfg.throttle_max, cfg.elevator_limit_deg, -cfg.aileron_limit_deg, 0.0f};
  ha_surfaces_to_pulses_us(&cfg, &s, pulses);
  EXPECT_EQ(pulses[HA_U_THROTTLE], cfg.servo_pulse_max_us);
  EXPECT_EQ(pulses[HA_U_ELEVATOR_DEG], cfg.servo_pulse_max_us);
  EXPECT_EQ(pulses[HA_U_AILERON_DEG], cfg.servo_pulse_min_us);
  EXPECT_EQ(pulses[HA_U_RUDDER_DEG], (cfg.servo_pulse_min_us + cfg.servo_pulse_max_us) / 2u);
  // Whatever slips through, a servo never gets a full deflection out of a NaN.
  s = {NAN, NAN, INFINITY, -INFINITY};
  ha_surfaces_to_pulses_us(&cfg, &s, pulses);
  EXPECT_EQ(pulses[HA_U_THROTTLE], cfg.servo_pulse_min_us);  // idle
  EXPECT_EQ(pulses[HA_U_ELEVATOR_DEG], (cfg.servo_pulse_min_us + cfg.servo_pulse_max_us) / 2u);
  EXPECT_EQ(pulses[HA_U_AILERON_DEG], cfg.servo_pulse_max_us);
  EXPECT_EQ(pulses[HA_U_RUDDER_DEG], cfg.servo_pulse_min_us);
}

}  // namespace
