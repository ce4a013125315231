// The aircraft configuration is generated from limits.yaml; arduino-cli compiles a checked-in
// copy, which must never drift from the YAML.
#include <gtest/gtest.h>

#include <string>

#include "ha_aircraft.h"
#include "limits_generator.h"

namespace {

TEST(HaGeneratedConfig, GeneratedConfigMatchesCheckedInCopy) {
  std::string fresh;
  ASSERT_EQ(RunGenerator(HA_LIMITS_YAML, &fresh), 0);
  ASSERT_FALSE(fresh.empty());
  EXPECT_EQ(fresh, Slurp(HA_CHECKED_IN_CONFIG))
      << "run: tools/stack_tools/gen_aircraft_config.py aircraft/DG808/limits.yaml "
         "arduino_ha/src/generated/aircraft_config.h";
}

TEST(HaGeneratedConfig, CarriesTheYamlLimits) {
  // Spot checks against the documented DG808 figures (issue 3 and limits.yaml).
  EXPECT_STREQ(ha_aircraft_config.aircraft, "DG808");
  EXPECT_FLOAT_EQ(ha_aircraft_config.aileron_limit_deg, 15.0f);
  EXPECT_FLOAT_EQ(ha_aircraft_config.elevator_limit_deg, 20.0f);
  EXPECT_FLOAT_EQ(ha_aircraft_config.ceiling_agl_ft, 400.0f);
  EXPECT_EQ(ha_aircraft_config.period_us, 10000u);
  EXPECT_EQ(ha_aircraft_config.su_rows, 8u);
  // Slopes the generator derives for the pilot's sticks: the full pulse range spans S_u.
  const HaAircraftConfig& c = ha_aircraft_config;
  const float span_us = static_cast<float>(c.rc_pulse_max_us - c.rc_pulse_min_us);
  EXPECT_FLOAT_EQ(c.rc_elevator_deg_per_us * span_us, 2.0f * c.elevator_limit_deg);
  EXPECT_FLOAT_EQ(c.rc_aileron_deg_per_us * span_us, 2.0f * c.aileron_limit_deg);
  EXPECT_FLOAT_EQ(c.rc_rudder_deg_per_us * span_us, 2.0f * c.rudder_limit_deg);
  EXPECT_FLOAT_EQ(c.rc_throttle_per_us * span_us, c.throttle_max - c.throttle_min);
}

// The safety controller's configuration-only values are the generator's (ha_config.h), said to be
// what ha_safety_ctrl.c computed every period, to the bit. Each is recomputed here from its
// sources as that code did in float arithmetic: a generator that drifts from its sources, or a
// source edited in the header alone, fails here rather than in a flight.
TEST(HaGeneratedConfig, DerivedSafetyControllerValuesAreTheirSourcesToTheBit) {
  const HaAircraftConfig& c = ha_aircraft_config;
  const float auth = c.sc_integrator_authority;
  const float half = 0.5f * (c.throttle_max - c.throttle_min);
  const float mid = c.throttle_min + half;
  EXPECT_EQ(c.sc_target_ftps, c.stall_speed_ftps * c.sc_cruise_margin);
  EXPECT_EQ(c.sc_speed_floor_ftps, c.stall_speed_ftps * c.sc_stall_margin);
  EXPECT_EQ(c.sc_alt_mid_ft, 0.5f * (c.sc_alt_min_ft + c.sc_alt_max_ft));
  EXPECT_EQ(c.sc_throttle_half, half);
  EXPECT_EQ(c.sc_throttle_mid, mid);
  EXPECT_EQ(c.sc_throttle_trim_offset, c.sc_throttle_trim - mid);
  EXPECT_EQ(c.sc_power_throttle_max, c.throttle_max - c.sc_throttle_trim);
  EXPECT_EQ(c.sc_aileron_integ_limit, auth * c.aileron_limit_deg);
  EXPECT_EQ(c.sc_elevator_integ_limit, auth * c.elevator_limit_deg);
  EXPECT_EQ(c.sc_throttle_integ_limit, auth * half);
  EXPECT_EQ(c.sc_blind_fade_auth_per_s, c.sc_blind_fade_per_s * auth);
}

TEST(HaGeneratedConfig, GeneratorRefusesBandAboveCeiling) {
  EXPECT_NE(GenerateWith("alt_max_ft", "399.0"), 0);
}

TEST(HaGeneratedConfig, GeneratorRefusesABootTimeoutThatKeepsADeadHpFromTheLatch) {
  // 3 x (0.1 + 20) s > 60 s: the first reset leaves the window before the cap is reached.
  EXPECT_NE(GenerateWith("hp_boot_timeout_s", "20.0"), 0);
  EXPECT_EQ(GenerateWith("hp_boot_timeout_s", "19.0"), 0);
  EXPECT_EQ(ha_aircraft_config.hp_boot_timeout_us, 15000000u);
}

// The safety controller flies about limits.yaml's elevator trim, and a blind HA holds it: a trim
// the airframe does not fly level with at the target speed would hold a climb or a dive.
TEST(HaGeneratedConfig, GeneratorRefusesAnElevatorTrimTheAirframeDoesNotFlyLevelWith) {
  ExpectRefused("elevator_trim_deg", "2.0", {"elevator_trim_deg = 2", "airframe.yaml"});
  // A trim its own elevator stop would not let the HA fly.
  ExpectRefused("elevator_trim_deg", "-3.0", {"elevator stop"});
  EXPECT_NE(GenerateWith("elevator_trim_deg", "21.0"), 0);  // past the surface's limit
  std::string fine;
  EXPECT_EQ(GenerateWith("elevator_trim_deg",
                         std::to_string(ha_aircraft_config.sc_elevator_trim_deg + 0.1f), &fine),
            0)
      << fine;
}

TEST(HaGeneratedConfig, GeneratorRefusesWhatTheCoreCannotHoldNamingKeyAndReason) {
  struct Case {
    const char* key;
    const char* value;
    const char* reason;  // a word the message must contain
  };
  const Case cases[] = {
      {"body_rate_limit_deg_per_s", "1.0e+46", "float"},  // its S_x rows vanish to zero
      {"max_airspeed_ftps", "1.0e+39", "float"},          // overflows to inf
      {"stable_window_s", "4.0e-7", "0 us"},              // rounds to no time at all
      {"max_restarts", "1.9", "whole"},                   // silently 1
      {"late_periods_tolerated", "1.5", "whole"},
      {"pulse_min_us", "1000.5", "whole"},
      {"no_command_timeout_s", "0.005", "period"},  // shorter than one period
      {"state_timeout_s", "0.004", "period"},
      {"late_periods_tolerated", "5", "no_command_timeout_s"},  // the timeout fires first
  };
  for (const Case& c : cases) {
    ExpectRefused(c.key, c.value, {c.key, c.reason});
  }
  std::string message;
  EXPECT_EQ(GenerateWith("max_restarts", "3", &message), 0) << message;
}

}  // namespace
