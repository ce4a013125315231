// The safety regions S_x x <= 1 and S_u u <= 1 as generated from limits.yaml.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "ha_aircraft.h"
#include "ha_board.h"
#include "ha_core.h"

extern "C" {
#include "ha_num.h"
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

// The core evaluates the thesis's general polytope S_x (x - x0) <= 1, not only the generator's
// centred boxes: a region centred on a cruise height whose one row couples two states (the
// steeper the bank, the more height it wants below the ceiling) judges a state by their sum,
// about the centre.
TEST(HaSafetyRegion, APolytopeRowCouplingTwoStatesAboutAnOffCentreIsJudgedOnTheirSum) {
  HaAircraftConfig poly = cfg;
  std::memset(poly.x0, 0, sizeof poly.x0);
  poly.sx_rows = 1u;
  poly.sx_row_end[0] = 2u;
  poly.x0[HA_X_ALT_AGL_FT] = 200.0f;
  poly.sx[0] = {HA_X_ROLL_DEG, 1.0f / 60.0f};     // 60 deg of bank alone ...
  poly.sx[1] = {HA_X_ALT_AGL_FT, 1.0f / 200.0f};  // ... or 200 ft above the centre alone
  float x[HA_X_DIM] = {};
  x[HA_X_ALT_AGL_FT] = 200.0f;
  x[HA_X_ROLL_DEG] = 30.0f;
  EXPECT_NEAR(ha_state_region_max(&poly, x), 0.5f, 1e-6f);  // at the centre: the bank's half
  x[HA_X_ALT_AGL_FT] = 300.0f;
  EXPECT_NEAR(ha_state_region_max(&poly, x), 1.0f, 1e-6f);  // half the bank + half the height
  x[HA_X_ALT_AGL_FT] = 310.0f;
  EXPECT_GT(ha_state_region_max(&poly, x), 1.0f);  // neither alone is past its edge
}

// A hand-made S_x whose whole term table is 1/60 of the roll, centred on 0: its rows are set by
// row_end alone.
HaAircraftConfig EveryTermRollOverSixty() {
  HaAircraftConfig poly = cfg;
  std::memset(poly.x0, 0, sizeof poly.x0);
  for (auto& term : poly.sx) term = {HA_X_ROLL_DEG, 1.0f / 60.0f};
  return poly;
}

// A hand-made configuration whose row claims terms past the table reads no further than the
// table: the row is judged on the terms there are.
TEST(HaSafetyRegion, ARowEndPastTheTermTableStopsAtItsEnd) {
  HaAircraftConfig poly = EveryTermRollOverSixty();
  poly.sx_rows = 1u;
  poly.sx_row_end[0] = 255u;  // past HA_SX_MAX_TERMS
  float x[HA_X_DIM] = {};
  x[HA_X_ROLL_DEG] = 1.0f;
  EXPECT_NEAR(ha_state_region_max(&poly, x), HA_SX_MAX_TERMS / 60.0f, 1e-4f);
}

// ... and a row with no terms, or one that begins where the table has run out, reads 0: inside,
// never garbage from beyond the table.
TEST(HaSafetyRegion, RowsWithoutTermsReadZero) {
  HaAircraftConfig poly = EveryTermRollOverSixty();
  poly.sx_rows = 3u;
  poly.sx_row_end[0] = 0u;    // no terms
  poly.sx_row_end[1] = 255u;  // the whole table
  poly.sx_row_end[2] = 255u;  // begins past the table
  float x[HA_X_DIM] = {};
  x[HA_X_ROLL_DEG] = 1.0f;
  EXPECT_NEAR(ha_state_region_max(&poly, x), HA_SX_MAX_TERMS / 60.0f, 1e-4f);
  x[HA_X_ROLL_DEG] = -1.0f;  // the full row negative: the empty rows' 0 is the most
  EXPECT_EQ(ha_state_region_max(&poly, x), 0.0f);
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

// The state view's plausibility checks decide |v| <= span on the float's bits (integer work on
// the FPU-less Due). They must agree with the float comparison for every bit pattern.
TEST(HaNumbers, BitwiseSpanCheckAgreesWithFloatCompareForEveryKindOfValue) {
  const float spans[] = {0.0f, 1e-40f, 90.0f, 180.0f, 2000.0f, 1.0e5f, 1.0e6f};
  std::vector<uint32_t> patterns = {0x00000000u, 0x80000000u, 0x00000001u, 0x807FFFFFu,
                                    0x7F800000u, 0xFF800000u, 0x7FC00000u, 0xFFC00001u,
                                    0x7F7FFFFFu, 0xFF7FFFFFu};
  uint32_t state = 0x12345678u;
  for (int i = 0; i < 2000000; ++i) {
    state = state * 1664525u + 1013904223u;  // reproducible LCG over all 2^32 patterns
    patterns.push_back(state);
  }
  for (float span : spans) {
    uint32_t span_bits;
    std::memcpy(&span_bits, &span, sizeof span_bits);
    patterns.push_back(span_bits);
    patterns.push_back(span_bits + 1u);
    patterns.push_back(span_bits | 0x80000000u);
    patterns.push_back((span_bits + 1u) | 0x80000000u);
  }
  for (float span : spans) {
    for (uint32_t bits : patterns) {
      float v;
      std::memcpy(&v, &bits, sizeof v);
      ASSERT_EQ(ha_in_range(v, -span, span), ha_within_span(v, span))
          << std::hex << "bits 0x" << bits << " span " << span;
    }
  }
}
