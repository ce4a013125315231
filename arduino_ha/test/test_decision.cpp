// The HA decision logic, one scripted timeline per behaviour: a fake board, a simulated clock
// and an HP that sends (or stops sending) commands.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <tuple>
#include <vector>

#include "ha_ins.h"
#include "ha_test_util.h"

namespace {

TEST(HaDecision, BootsOnHaAndHandsOverAfterStableWindow) {
  Timeline t;
  t.Step();
  EXPECT_EQ(t.controller(), HA_CONTROLLER_HA);
  EXPECT_TRUE(t.out().reasons & HA_REASON_NO_COMMAND);
  EXPECT_EQ(t.out().restart_count, 0u);  // booting is not a failure
  const int periods = t.ReachHp();
  const int window = static_cast<int>(t.cfg.stable_window_us / t.cfg.period_us);
  EXPECT_GE(periods, window);
  EXPECT_LE(periods, window + 2);
}

void HpCrashSwitchesAfterTolerance(uint32_t tolerated) {
  HaAircraftConfig cfg = ha_aircraft_config;
  cfg.late_periods_tolerated = tolerated;
  Timeline t(cfg);
  ASSERT_GT(t.ReachHp(), 0);
  t.StepWithGood(3.0f);
  const HaSurfaces last_hp = t.servos();
  // The HP process dies: nothing more arrives. Every tolerated late period holds its command.
  for (uint32_t late = 1; late <= tolerated; ++late) {
    t.Step();
    EXPECT_EQ(t.controller(), HA_CONTROLLER_HP) << "late period " << late;
    EXPECT_FLOAT_EQ(t.servos().aileron_deg, last_hp.aileron_deg);
  }
  // The next missed deadline switches, in that very period.
  t.Step();
  EXPECT_EQ(t.controller(), HA_CONTROLLER_HA);
  EXPECT_TRUE(t.out().reasons & HA_REASON_DEADLINE_MISS);
  EXPECT_TRUE(t.out().reasons_at_switch & HA_REASON_DEADLINE_MISS);
  EXPECT_EQ(t.out().restart_requested, 1u);
  EXPECT_EQ(t.out().restart_count, 1u);
  EXPECT_TRUE(t.board.hp_reset);
  // Later the no-command timeout reports the crash for what it is; the reset pulse ends.
  for (int i = 0; i < 20; ++i) t.Step();
  EXPECT_EQ(t.controller(), HA_CONTROLLER_HA);
  EXPECT_TRUE(t.out().reasons & HA_REASON_NO_COMMAND);
  EXPECT_FALSE(t.board.hp_reset);
  EXPECT_EQ(t.board.hp_reset_assertions, 1);
}

TEST(HaDecision, HpCrashSwitchesWithinOnePeriodAfterDeadline) {
  HpCrashSwitchesAfterTolerance(ha_aircraft_config.late_periods_tolerated);
  HpCrashSwitchesAfterTolerance(0u);  // no tolerance: the first missed deadline switches
}

TEST(HaDecision, OneLatePeriodToleratedTwoSwitch) {
  ASSERT_EQ(ha_aircraft_config.late_periods_tolerated, 1u);
  Timeline t;
  ASSERT_GT(t.ReachHp(), 0);
  // An HP that misses every other deadline stays in control for a long time.
  for (int i = 0; i < 300; ++i) {
    t.StepWithGood(static_cast<float>(i % 7));
    ASSERT_EQ(t.controller(), HA_CONTROLLER_HP);
    const float commanded = t.servos().aileron_deg;
    t.Step();
    ASSERT_EQ(t.controller(), HA_CONTROLLER_HP) << "single late period at " << i;
    ASSERT_EQ(t.out().reasons, 0u);
    ASSERT_FLOAT_EQ(t.servos().aileron_deg, commanded);  // the last command is held
  }
  // Two in a row do not.
  t.StepWithGood();
  t.Step();
  EXPECT_EQ(t.controller(), HA_CONTROLLER_HP);
  t.Step();
  EXPECT_EQ(t.controller(), HA_CONTROLLER_HA);
  EXPECT_EQ(t.out().reasons_at_switch, HA_REASON_DEADLINE_MISS);
}

TEST(HaDecision, NanAileronNeverReachesServo) {
  Timeline t;
  ASSERT_GT(t.ReachHp(), 0);
  HaHpCommand bad = MakeCommand(t.NextSeq(), 0.5f, 0.0f, std::numeric_limits<float>::quiet_NaN(),
                                0.0f);  // CRC is valid: the HP really computed a NaN
  t.StepWith(bad);
  EXPECT_EQ(t.controller(), HA_CONTROLLER_HA);
  EXPECT_TRUE(t.out().reasons & HA_REASON_NOT_FINITE);
  EXPECT_FALSE(t.out().reasons & HA_REASON_INTEGRITY);
  bad.aileron_deg = std::numeric_limits<float>::infinity();
  bad.seq = t.NextSeq();
  SealCommand(&bad);
  t.StepWith(bad);
  for (const HaSurfaces& s : t.board.servo_writes) {
    ASSERT_TRUE(SurfacesInside(t.cfg, s));
  }
  EXPECT_TRUE(std::isfinite(t.out().actuator_region_max));
}

TEST(HaDecision, CommandOutsideActuatorRegionSwitches) {
  Timeline t;
  ASSERT_GT(t.ReachHp(), 0);
  t.StepWithGood(0.0f, t.cfg.elevator_limit_deg + 0.5f);
  EXPECT_EQ(t.controller(), HA_CONTROLLER_HA);
  EXPECT_EQ(t.out().reasons, HA_REASON_ACTUATOR_REGION);
  EXPECT_GT(t.out().actuator_region_max, 1.0f);
  EXPECT_LE(std::fabs(t.servos().elevator_deg), t.cfg.elevator_limit_deg);
}

// The low_slow HiL flight: the HP pulls the elevator full up at 84 ft/s. The stall check sees it
// only once the wing is loaded (4 g, stalled 0.16 s after the command); the command itself says
// it: full up trims the wing far past its stall. The HA refuses it the period it arrives, so
// the servo never moves towards it.
TEST(HaDecision, HpPullingFullUpAtCruiseIsRefusedBeforeTheElevatorMoves) {
  Timeline t;
  ASSERT_GT(t.ReachHp(), 0);
  const float before_deg = t.servos().elevator_deg;
  t.StepWithGood(0.0f, -t.cfg.elevator_limit_deg);
  EXPECT_EQ(t.controller(), HA_CONTROLLER_HA);
  EXPECT_TRUE(t.out().reasons & HA_REASON_PULL) << t.out().reasons;
  EXPECT_GE(t.servos().elevator_deg, before_deg - 0.01f) << "the pull reached the servo";
  // The HA's own elevator stays inside its stop while it flies.
  for (int i = 0; i < 300; ++i) {
    t.StepWithGood(0.0f, -t.cfg.elevator_limit_deg);
    ASSERT_GE(t.servos().elevator_deg, -t.cfg.sc_elevator_pull_max_deg - 1e-4f) << i;
  }
}

// The HP's own pulls in gusts (HiL: 4.9 deg at most in moderate turbulence) are no fault.
TEST(HaDecision, HpPullInsideThePullLimitKeepsControl) {
  Timeline t;
  ASSERT_GT(t.ReachHp(), 0);
  for (int i = 0; i < 100; ++i) {
    t.StepWithGood(0.0f, -0.95f * t.cfg.elevator_pull_limit_deg);
  }
  EXPECT_EQ(t.controller(), HA_CONTROLLER_HP) << t.out().reasons;
  EXPECT_FLOAT_EQ(t.servos().elevator_deg, -0.95f * t.cfg.elevator_pull_limit_deg);
}

// On the ground a full pull holds the tail down on the take-off run: not a fault.
TEST(HaDecision, FullPullParkedOnTheGroundIsNoFault) {
  Timeline t;
  t.Parked();
  for (int i = 0; i < 50; ++i) {
    t.StepWithGood(0.0f, -t.cfg.elevator_limit_deg);
    ASSERT_EQ(t.out().reasons & HA_REASON_PULL, 0u) << i;
  }
}

// An HP climbing through the ceiling, seen by an INS that reads 5 ft low: the HA switches
// within its margin of the ceiling, and the true height never reaches it.
TEST(HaDecision, ClimbTowardsTheCeilingIsTakenOverBeforeItWithAnInsReadingLow) {
  Timeline t;
  ASSERT_GT(t.ReachHp(), 0);
  const float ins_low_ft = 5.0f;
  PointMassAircraft ac;
  ac.north_ft = t.cfg.sc_circle_radius_ft;
  ac.heading_deg = 90.0f;
  ac.altitude_ft = t.cfg.ceiling_switch_agl_ft - 30.0f;
  ac.pitch_deg = 8.0f;  // the HP is climbing through the ceiling
  ac.airspeed_ftps = 65.0f;
  bool switched = false;
  float peak_ft = 0.0f;
  for (int i = 0; i < 100 * 150; ++i) {
    ac.WriteTo(&t.app.inputs, t.board.now_us);
    t.app.inputs.altitude_agl_ft -= ins_low_ft;
    t.board.airspeed_ftps = ac.airspeed_ftps;
    t.refresh_state = false;
    if (i < 100 * 30) {
      t.StepWithGood(0.0f, -0.4f, 0.0f, 0.8f);  // a healthy HP that keeps climbing...
    } else {
      t.Step();  // ...until it is gone, and the HA alone flies
    }
    if (!switched && t.controller() != HA_CONTROLLER_HP) {
      switched = true;
      EXPECT_LT(ac.altitude_ft, t.cfg.ceiling_agl_ft);
      EXPECT_TRUE(t.out().reasons_at_switch & HA_REASON_CEILING);
    }
    ac.Step(t.servos(), t.cfg.period_us * 1e-6f);
    peak_ft = std::max(peak_ft, ac.altitude_ft);
  }
  ASSERT_TRUE(switched);
  EXPECT_LT(peak_ft, t.cfg.ceiling_agl_ft);
  // Two minutes on the HA alone: it holds the aircraft inside its band, well below the ceiling.
  EXPECT_LE(ac.altitude_ft, t.cfg.sc_alt_max_ft);
  EXPECT_GE(ac.altitude_ft, t.cfg.sc_alt_min_ft);
}

// An HP rolling steadily out past the roll limit (every command valid): the HA has the servos
// before the limit, and while its controller slews in from the HP's aileron the roll it
// inherits never reaches the limit.
TEST(HaDecision, RollOutTowardsTheLimitIsTakenOverAndStoppedInsideIt) {
  Timeline t;
  ASSERT_GT(t.ReachHp(), 0);
  const float roll_limit = 1.0f / t.cfg.sx[4].coef;  // row 4: +roll, its one term
  PointMassAircraft ac;
  ac.north_ft = t.cfg.sc_circle_radius_ft;
  ac.heading_deg = 90.0f;
  ac.airspeed_ftps = 62.0f;
  bool switched = false;
  float peak_deg = 0.0f;
  for (int i = 0; i < 100 * 20; ++i) {
    ac.WriteTo(&t.app.inputs, t.board.now_us);
    t.board.airspeed_ftps = ac.airspeed_ftps;
    t.refresh_state = false;
    t.StepWithGood(4.0f, -1.0f, 0.0f, 0.5f);  // 16 deg/s of roll, for as long as it is obeyed
    if (!switched && t.controller() != HA_CONTROLLER_HP) {
      switched = true;
      EXPECT_LT(ac.roll_deg, roll_limit);
      EXPECT_TRUE(t.out().reasons_at_switch & HA_REASON_STATE_REGION);
      EXPECT_LT(t.out().state_region_max, 1.0f);
    }
    ac.Step(t.servos(), t.cfg.period_us * 1e-6f);
    peak_deg = std::max(peak_deg, std::fabs(ac.roll_deg));
  }
  ASSERT_TRUE(switched);
  EXPECT_LT(peak_deg, roll_limit);
}

// Slowing towards the stall: the pitot lags, so the HA takes over above stall speed, at its
// switch speed, and lowers the nose while there is still lift to fly with.
TEST(HaDecision, SlowingTowardsTheStallIsTakenOverAboveStallSpeed) {
  Timeline t;
  ASSERT_GT(t.ReachHp(), 0);
  t.board.airspeed_ftps = 0.5f * (t.cfg.stall_speed_ftps + t.cfg.stall_switch_airspeed_ftps);
  ASSERT_GT(t.board.airspeed_ftps, t.cfg.stall_speed_ftps);
  t.StepWithGood();
  EXPECT_EQ(t.controller(), HA_CONTROLLER_HA);
  EXPECT_EQ(t.out().reasons_at_switch, HA_REASON_STALL);
  for (int i = 0; i < 50; ++i) t.StepWithGood();
  EXPECT_GT(t.servos().elevator_deg, 0.0f);  // trailing edge down: nose down
}

TEST(HaDecision, StallWhileAirborneSwitches) {
  Timeline t;
  ASSERT_GT(t.ReachHp(), 0);
  t.board.airspeed_ftps = t.cfg.stall_speed_ftps - 1.0f;
  t.StepWithGood();
  EXPECT_EQ(t.controller(), HA_CONTROLLER_HA);
  EXPECT_EQ(t.out().reasons_at_switch, HA_REASON_STALL);
  // The HA pushes the nose down and opens the throttle to regain speed.
  for (int i = 0; i < 50; ++i) t.StepWithGood();
  EXPECT_GT(t.servos().elevator_deg, 0.0f);
  EXPECT_GT(t.servos().throttle, t.cfg.sc_throttle_trim);
}

// A pitot that reads zero in cruise (blocked, zeroed) while the INS shows 60 ft/s over the
// ground: no tailwind explains it, so it is a lying sensor, not a stall. Believed, the
// slow-beats-low law would push the nose down all the way to the ground; instead the HA takes
// the servos for its own missing airspeed (no HP reset), and flies the altitude band.
TEST(HaDecision, AZeroPitotInCruiseIsALyingSensorNotAStallToDiveOutOf) {
  Timeline t;
  t.Cruise(200.0f, 60.0f);
  ASSERT_GT(t.ReachHp(), 0);
  t.board.airspeed_ftps = 0.0f;
  for (uint32_t i = 0; i <= t.cfg.airspeed_timeout_us / t.cfg.period_us + 1u; ++i) t.StepWithGood();
  EXPECT_NE(t.controller(), HA_CONTROLLER_HP);
  EXPECT_EQ(t.out().reasons_at_switch, HA_REASON_NO_HA_STATE);
  EXPECT_FALSE(t.out().reasons & HA_REASON_STALL);
  EXPECT_EQ(t.out().restart_count, 0u);
  EXPECT_EQ(t.board.hp_reset_assertions, 0);
  for (int i = 0; i < 300; ++i) t.StepWithGood();  // past the bumpless slew
  // At the band's middle, level: no dive (trailing edge down beyond a trim's worth).
  t.app.inputs.altitude_agl_ft = 0.5f * (t.cfg.sc_alt_min_ft + t.cfg.sc_alt_max_ft);
  for (int i = 0; i < 300; ++i) t.StepWithGood();
  EXPECT_LT(t.servos().elevator_deg, 0.25f * t.cfg.elevator_limit_deg);
  // A slow reading a tailwind can explain is still believed: a stall downwind is a stall.
  Timeline u;
  u.Cruise(200.0f, 60.0f);
  ASSERT_GT(u.ReachHp(), 0);
  u.board.airspeed_ftps = u.app.inputs.groundspeed_ftps - 0.9f * u.cfg.max_wind_ftps;
  ASSERT_LT(u.board.airspeed_ftps, u.cfg.stall_switch_airspeed_ftps);
  u.StepWithGood();
  EXPECT_EQ(u.out().reasons_at_switch, HA_REASON_STALL);
}

TEST(HaDecision, NoAirspeedOnTheGroundIsNoStall) {
  Timeline t;
  t.Parked();
  ASSERT_GT(t.ReachHp(), 0);
  EXPECT_EQ(t.out().reasons, 0u);
  // A pitot dead in flight (longer than a glitch) leaves the HA unable to check for a stall: it
  // takes control and says why, and that is not a stall.
  t.Cruise();
  for (int i = 0; i < 100; ++i) t.StepWithGood();
  ASSERT_EQ(t.controller(), HA_CONTROLLER_HP);
  t.board.airspeed_ok = false;
  for (uint32_t i = 0; i <= t.cfg.airspeed_timeout_us / t.cfg.period_us; ++i) t.StepWithGood();
  EXPECT_NE(t.controller(), HA_CONTROLLER_HP);
  EXPECT_EQ(t.out().reasons, HA_REASON_NO_HA_STATE);
  EXPECT_EQ(t.out().reasons_at_switch, HA_REASON_NO_HA_STATE);
}

TEST(HaDecision, SwitchBackOnlyAfterStableWindowInsideInnerRegion) {
  Timeline t;
  ASSERT_GT(t.ReachHp(), 0);
  HaHpCommand glitch = MakeCommand(t.NextSeq(), 0.5f, 0.0f, 0.0f, 0.0f);
  glitch.sensor_links_healthy = 0;
  SealCommand(&glitch);
  t.StepWith(glitch);
  ASSERT_EQ(t.controller(), HA_CONTROLLER_HA);
  // Roll between the inner and the outer region: inside S_x, not inside the inner region.
  const float roll_limit = 1.0f / t.cfg.sx[4].coef;  // row 4: +roll, its one term
  t.app.inputs.roll_deg = roll_limit * 0.5f * (1.0f + t.cfg.inner_region_fraction);
  const int window = static_cast<int>(t.cfg.stable_window_us / t.cfg.period_us);
  for (int i = 0; i < 3 * window; ++i) {
    t.StepWithGood();
    ASSERT_EQ(t.controller(), HA_CONTROLLER_RECOVERING) << "period " << i;
    ASSERT_EQ(t.out().reasons, 0u);
  }
  EXPECT_GT(t.out().stable_for_s, 2.9f * t.cfg.stable_window_us * 1e-6f);
  // Back inside the inner region: handed back at once, the window having elapsed.
  t.app.inputs.roll_deg = 0.0f;
  t.StepWithGood();
  EXPECT_EQ(t.controller(), HA_CONTROLLER_HP);

  // Inside the inner region but a command glitch restarts the window.
  t.StepWith(glitch);
  ASSERT_EQ(t.controller(), HA_CONTROLLER_HA);
  int periods = 0;
  for (; periods < 3 * window && t.controller() != HA_CONTROLLER_HP; ++periods) {
    t.StepWithGood();
    if (periods == window / 2) {
      t.StepWith(glitch);  // invalid again halfway through: back to HA, window restarts
      ASSERT_EQ(t.controller(), HA_CONTROLLER_HA);
    }
  }
  EXPECT_EQ(t.controller(), HA_CONTROLLER_HP);
  EXPECT_GE(periods, window + window / 2);
}

TEST(HaDecision, PilotSwitchBeatsEverything) {
  Timeline t;
  t.board.SetPilotInCommand(true);
  t.board.rc.pulse_us[HA_RC_AILERON] = 2000;  // full right
  t.board.rc.pulse_us[HA_RC_THROTTLE] = 1500;
  // No HP, a stall, above the ceiling, a ground command, NaN commands: the pilot flies.
  t.Cruise(t.cfg.ceiling_agl_ft + 50.0f, t.cfg.stall_speed_ftps - 5.0f);
  t.Operator(HA_OP_SELECT_HA);
  HaHpCommand nan_cmd = MakeCommand(t.NextSeq(), NAN, NAN, NAN, NAN);
  for (int i = 0; i < 300; ++i) {
    nan_cmd.seq = t.NextSeq();
    SealCommand(&nan_cmd);
    t.StepWith(nan_cmd);
    ASSERT_EQ(t.controller(), HA_CONTROLLER_MANUAL);
  }
  EXPECT_FLOAT_EQ(t.servos().aileron_deg, t.cfg.aileron_limit_deg);
  EXPECT_FLOAT_EQ(t.servos().throttle, 0.5f * (t.cfg.throttle_min + t.cfg.throttle_max));
  EXPECT_EQ(t.board.leds & HA_LED_MANUAL, HA_LED_MANUAL);
  // Even a latched HA yields to the pilot.
  HaAircraftConfig one = ha_aircraft_config;
  one.max_restarts = 1;
  Timeline l(one);
  ASSERT_GT(l.ReachHp(), 0);
  l.Step();
  l.Step();  // crash 1: restart
  ASSERT_GT(l.ReachHp(), 0);
  l.Step();
  l.Step();  // crash 2: latched
  ASSERT_EQ(l.controller(), HA_CONTROLLER_HA_LATCHED);
  l.board.SetPilotInCommand(true);
  l.Step();
  EXPECT_EQ(l.controller(), HA_CONTROLLER_MANUAL);
  l.board.SetPilotInCommand(false);
  l.Step();
  EXPECT_EQ(l.controller(), HA_CONTROLLER_HA_LATCHED);
  // A dead receiver cannot claim PIC: the HA flies.
  t.board.rc.valid = 0;
  t.Step();
  EXPECT_NE(t.controller(), HA_CONTROLLER_MANUAL);
}

TEST(HaDecision, RestartCapLatchesHa) {
  Timeline t;
  const uint32_t k = t.cfg.max_restarts;
  ASSERT_GE(k, 1u);
  for (uint32_t crash = 1; crash <= k; ++crash) {
    ASSERT_GT(t.ReachHp(), 0) << "recovery " << crash;
    t.Step();
    t.Step();
    ASSERT_EQ(t.controller(), HA_CONTROLLER_HA);
    ASSERT_EQ(t.out().restart_count, crash);
    for (int i = 0; i < 20; ++i) t.Step();  // the HP reboots
  }
  // Recovery K+1 fails too, well inside T: that was one too many.
  ASSERT_GT(t.ReachHp(), 0);
  t.Step();
  t.Step();
  EXPECT_EQ(t.controller(), HA_CONTROLLER_HA_LATCHED);
  EXPECT_EQ(t.out().restart_count, k);  // no further restart is requested
  EXPECT_EQ(t.board.hp_reset_assertions, static_cast<int>(k));
  // A perfect HP and an operator asking for it change nothing.
  t.Operator(HA_OP_SELECT_HP);
  for (int i = 0; i < 1000; ++i) t.StepWithGood();
  EXPECT_EQ(t.controller(), HA_CONTROLLER_HA_LATCHED);
  EXPECT_EQ(t.app.requests.ack_accepted, 0u);
}

TEST(HaDecision, HpThatNeverReturnsIsRestartedUntilTheCapThenLatched) {
  Timeline t;
  const uint32_t k = t.cfg.max_restarts;
  const uint32_t spacing_us = t.cfg.hp_reset_pulse_us + t.cfg.hp_boot_timeout_us;
  ASSERT_GT(t.ReachHp(), 0);
  for (int i = 0; i < 300; ++i) t.StepWithGood();  // three seconds of good flight
  ASSERT_EQ(t.controller(), HA_CONTROLLER_HP);
  // The HP dies and never produces another command, however often it is reset.
  std::vector<uint32_t> pulse_starts_us;
  uint32_t latched_at_us = 0;
  bool reset_before = t.board.hp_reset;
  const int periods = static_cast<int>((k + 2u) * spacing_us / t.cfg.period_us);
  for (int i = 0; i < periods; ++i) {
    t.Step();
    if (t.board.hp_reset && !reset_before) pulse_starts_us.push_back(t.board.now_us);
    reset_before = t.board.hp_reset;
    if (latched_at_us == 0u && t.controller() == HA_CONTROLLER_HA_LATCHED) {
      latched_at_us = t.board.now_us;
      EXPECT_TRUE(t.out().reasons_at_switch & HA_REASON_NO_COMMAND);  // why: the HP is silent
    }
    if (i >= static_cast<int>(t.cfg.late_periods_tolerated)) {
      ASSERT_NE(t.controller(), HA_CONTROLLER_HP) << "period " << i;
    }
  }
  // K resets, each one boot timeout after the previous one was released...
  ASSERT_EQ(pulse_starts_us.size(), k);
  for (size_t i = 1; i < pulse_starts_us.size(); ++i) {
    const uint32_t gap_us = pulse_starts_us[i] - pulse_starts_us[i - 1];
    EXPECT_GE(gap_us, spacing_us) << "reset " << i + 1;
    EXPECT_LE(gap_us, spacing_us + t.cfg.period_us) << "reset " << i + 1;
  }
  // ...then, one more boot timeout later, the latch instead of a reset K+1.
  ASSERT_NE(latched_at_us, 0u);
  EXPECT_GE(latched_at_us - pulse_starts_us.back(), spacing_us);
  EXPECT_LE(latched_at_us - pulse_starts_us.back(), spacing_us + t.cfg.period_us);
  EXPECT_EQ(t.controller(), HA_CONTROLLER_HA_LATCHED);
  EXPECT_EQ(t.out().restart_count, k);
  EXPECT_EQ(t.board.hp_reset_assertions, static_cast<int>(k));
  EXPECT_FALSE(t.board.hp_reset);
  EXPECT_EQ(t.board.leds, HA_LED_HA | HA_LED_FAULT);
}

// The HP earns control, then falls silent: two periods without a command are a crash, and the
// HA asks for restart 1.
::testing::AssertionResult HpFliesThenCrashes(Timeline* t) {
  if (t->ReachHp() <= 0) return ::testing::AssertionFailure() << "the HP never got control";
  t->Step();
  t->Step();
  if (t->out().restart_count == 1u) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "restarts after the crash: " << t->out().restart_count;
}

TEST(HaDecision, HpThatBootsWithinTheTimeoutIsNotResetAgain) {
  Timeline t;
  ASSERT_TRUE(HpFliesThenCrashes(&t));
  // A slow boot, just inside the timeout, then a healthy HP.
  const int boot_periods =
      static_cast<int>((t.cfg.hp_reset_pulse_us + t.cfg.hp_boot_timeout_us) / t.cfg.period_us);
  for (int i = 0; i < boot_periods - 2; ++i) t.Step();
  EXPECT_GT(t.ReachHp(), 0);
  EXPECT_EQ(t.out().restart_count, 1u);
  EXPECT_EQ(t.board.hp_reset_assertions, 1);
  // The operator's choice of the HA is no HP failure: choosing it resets nothing.
  t.Operator(HA_OP_SELECT_HA);
  t.StepWithGood();
  ASSERT_EQ(t.controller(), HA_CONTROLLER_HA);
  for (int i = 0; i < 2 * boot_periods; ++i) t.StepWithGood();
  EXPECT_EQ(t.controller(), HA_CONTROLLER_HA);
  EXPECT_EQ(t.out().restart_count, 1u);
}

TEST(HaDecision, HpThatKeepsFailingWhileRecoveringIsLatchedAtTheCap) {
  Timeline t;
  const uint32_t k = t.cfg.max_restarts;
  const int half_window = static_cast<int>(t.cfg.stable_window_us / t.cfg.period_us / 2u);
  ASSERT_TRUE(HpFliesThenCrashes(&t));
  for (uint32_t attempt = 1; attempt <= k; ++attempt) {
    // The HP reboots and sends good commands for half the stable window: watched, not used...
    for (int i = 0; i < 50; ++i) t.Step();
    for (int i = 0; i < half_window; ++i) {
      t.StepWithGood();
      ASSERT_EQ(t.controller(), HA_CONTROLLER_RECOVERING) << "attempt " << attempt;
    }
    // ...then a command outside S_u before the window is over.
    t.StepWithGood(0.0f, 2.0f * t.cfg.elevator_limit_deg);
    if (attempt < k) {
      ASSERT_EQ(t.controller(), HA_CONTROLLER_HA) << "attempt " << attempt;
      ASSERT_EQ(t.out().restart_count, attempt + 1u);
    }
  }
  // The K-th reset did not help either: latched, and said why.
  EXPECT_EQ(t.controller(), HA_CONTROLLER_HA_LATCHED);
  EXPECT_EQ(t.out().reasons_at_switch, HA_REASON_ACTUATOR_REGION);
  EXPECT_EQ(t.out().restart_count, k);
  EXPECT_EQ(t.board.hp_reset_assertions, static_cast<int>(k));
  // A good HP afterwards changes nothing, and nothing resets it any more.
  for (int i = 0; i < 100 * 60; ++i) t.StepWithGood();
  EXPECT_EQ(t.controller(), HA_CONTROLLER_HA_LATCHED);
  EXPECT_EQ(t.board.hp_reset_assertions, static_cast<int>(k));
}

TEST(HaDecision, RestartsSpreadBeyondWindowDoNotLatch) {
  Timeline t;
  const int window_periods = static_cast<int>(t.cfg.restart_window_us / t.cfg.period_us);
  for (uint32_t crash = 1; crash <= 2 * t.cfg.max_restarts; ++crash) {
    ASSERT_GT(t.ReachHp(), 0);
    t.Step();
    t.Step();
    ASSERT_EQ(t.controller(), HA_CONTROLLER_HA) << "crash " << crash;
    // Fly on the HP long enough that older restarts leave the window.
    ASSERT_GT(t.ReachHp(), 0);
    for (int i = 0; i < window_periods / static_cast<int>(t.cfg.max_restarts); ++i) {
      t.StepWithGood();
    }
  }
  EXPECT_EQ(t.out().restart_count, 2 * t.cfg.max_restarts);
}

TEST(HaDecision, FrozenSequenceNumberSwitches) {
  Timeline t;
  ASSERT_GT(t.ReachHp(), 0);
  const HaHpCommand stuck = MakeCommand(t.NextSeq(), 0.5f, 1.0f, 1.0f, 0.0f);
  t.StepWith(stuck);
  EXPECT_EQ(t.controller(), HA_CONTROLLER_HP);
  t.StepWith(stuck);  // arrives on time, but it is the same command again
  EXPECT_EQ(t.controller(), HA_CONTROLLER_HA);
  EXPECT_EQ(t.out().reasons_at_switch, HA_REASON_FROZEN);
  EXPECT_EQ(t.out().last_seq, stuck.seq);
}

TEST(HaDecision, SequenceNumberGoingBackwardsSwitches) {
  Timeline t;
  ASSERT_GT(t.ReachHp(), 0);
  const uint32_t ahead = t.NextSeq();
  t.StepWith(MakeCommand(ahead, 0.5f, 1.0f, 1.0f, 0.0f));
  EXPECT_EQ(t.controller(), HA_CONTROLLER_HP);
  t.StepWith(MakeCommand(ahead - 5u, 0.5f, 1.0f, 1.0f, 0.0f));  // a stale command replayed late
  EXPECT_EQ(t.controller(), HA_CONTROLLER_HA);
  EXPECT_EQ(t.out().reasons_at_switch, HA_REASON_FROZEN);
}

TEST(HaDecision, SequenceNumberWrapAroundIsNotAFault) {
  Timeline t;
  t.seq = 0xFFFFFFF0u;  // the HP's counter wraps while it earns control and while it flies
  ASSERT_GT(t.ReachHp(), 0);
  for (int i = 0; i < 40; ++i) {
    t.StepWith(MakeCommand(t.NextSeq(), 0.5f, 1.0f, 1.0f, 0.0f));
    ASSERT_EQ(t.controller(), HA_CONTROLLER_HP) << "seq " << t.seq;
  }
  EXPECT_LT(t.seq, 0x1000u);
}

TEST(HaDecision, CorruptCrcSwitches) {
  Timeline t;
  ASSERT_GT(t.ReachHp(), 0);
  HaHpCommand cmd = MakeCommand(t.NextSeq(), 0.5f, 0.0f, 4.0f, 0.0f);
  cmd.aileron_deg = 14.0f;  // one field changed after the CRC was computed
  t.StepWith(cmd);
  EXPECT_EQ(t.controller(), HA_CONTROLLER_HA);
  EXPECT_EQ(t.out().reasons_at_switch, HA_REASON_INTEGRITY);
  EXPECT_NE(t.servos().aileron_deg, 14.0f);
}

TEST(HaDecision, CorruptSequenceNumberDoesNotPoisonTheNextValidCommand) {
  Timeline t;
  ASSERT_GT(t.ReachHp(), 0);
  const uint32_t good_seq = t.seq;
  // A bit flipped on the wire in seq: a forward jump of 2^30 with a CRC that no longer fits.
  HaHpCommand corrupt = MakeCommand(t.NextSeq(), 0.5f, 0.0f, 1.0f, 0.0f);
  corrupt.seq ^= 0x40000000u;
  t.StepWith(corrupt);
  EXPECT_EQ(t.controller(), HA_CONTROLLER_HA);
  EXPECT_EQ(t.out().reasons, HA_REASON_INTEGRITY);  // the CRC, nothing else
  EXPECT_EQ(t.out().reasons_at_switch, HA_REASON_INTEGRITY);
  EXPECT_EQ(t.out().last_seq, good_seq);  // the corrupt frame's seq is not believed
  // The HP's next command is in order relative to the last intact one: no frozen/replay fault.
  t.StepWithGood();
  EXPECT_EQ(t.out().reasons, 0u);
  EXPECT_EQ(t.out().last_seq, t.seq);
  EXPECT_EQ(t.controller(), HA_CONTROLLER_RECOVERING);
  // And the same with the top bit flipped, which also looks like a step back.
  HaHpCommand flipped = MakeCommand(t.NextSeq(), 0.5f, 0.0f, 1.0f, 0.0f);
  flipped.seq ^= 0x80000000u;
  t.StepWith(flipped);
  EXPECT_EQ(t.out().reasons, HA_REASON_INTEGRITY);
  t.StepWithGood();
  EXPECT_EQ(t.out().reasons, 0u);
  EXPECT_GT(t.ReachHp(), 0);
}

TEST(HaDecision, EstimatorDivergenceAndNonConvergenceSwitch) {
  Timeline t;
  ASSERT_GT(t.ReachHp(), 0);
  HaHpCommand cmd = MakeCommand(t.NextSeq(), 0.5f, 0.0f, 0.0f, 0.0f);
  cmd.alpha_est_deg = t.cfg.alpha_limit_deg + 1.0f;
  SealCommand(&cmd);
  t.StepWith(cmd);
  EXPECT_EQ(t.controller(), HA_CONTROLLER_HA);
  EXPECT_TRUE(t.out().reasons_at_switch & HA_REASON_ALPHA_BETA);
  Timeline u;
  ASSERT_GT(u.ReachHp(), 0);
  cmd = MakeCommand(u.NextSeq(), 0.5f, 0.0f, 0.0f, 0.0f);
  cmd.estimator_converged = 0;
  SealCommand(&cmd);
  u.StepWith(cmd);
  EXPECT_EQ(u.controller(), HA_CONTROLLER_HA);
  EXPECT_EQ(u.out().reasons_at_switch, HA_REASON_ESTIMATOR);
}

TEST(HaDecision, StaleInsStateSwitches) {
  Timeline t;
  ASSERT_GT(t.ReachHp(), 0);
  t.refresh_state = false;  // the INS stops; the HP keeps sending
  int periods = 0;
  while (t.controller() == HA_CONTROLLER_HP && periods < 100) {
    t.StepWithGood();
    ++periods;
  }
  EXPECT_EQ(t.controller(), HA_CONTROLLER_HA);
  // Said as the HA lacking its own state (not a ceiling or region breach), and no HP fault.
  EXPECT_EQ(t.out().reasons_at_switch, HA_REASON_NO_HA_STATE);
  EXPECT_EQ(t.out().restart_count, 0u);
  EXPECT_EQ(t.board.hp_reset_assertions, 0);
  EXPECT_LE(static_cast<uint32_t>(periods) * t.cfg.period_us,
            t.cfg.state_timeout_us + 2u * t.cfg.period_us);
}

TEST(HaDecision, OperatorSelectsHaThenHpWithoutRestart) {
  Timeline t;
  ASSERT_GT(t.ReachHp(), 0);
  t.Operator(HA_OP_SELECT_HA);
  t.StepWithGood();
  EXPECT_EQ(t.controller(), HA_CONTROLLER_HA);
  EXPECT_EQ(t.out().reasons, HA_REASON_GROUND_COMMAND);
  EXPECT_EQ(t.out().restart_count, 0u);  // the operator's choice is no HP failure
  EXPECT_EQ(t.app.requests.ack_accepted, 1u);
  EXPECT_EQ(t.app.requests.ack_id, t.operator_id);
  for (int i = 0; i < 500; ++i) t.StepWithGood();
  EXPECT_EQ(t.controller(), HA_CONTROLLER_HA);
  t.Operator(HA_OP_SELECT_HP);
  EXPECT_GT(t.ReachHp(), 0);
}

TEST(HaDecision, OperatorRestartPulsesResetLine) {
  Timeline t;
  t.Step();
  t.Operator(HA_OP_RESTART_HP);
  t.Step();
  EXPECT_EQ(t.out().restart_requested, 1u);
  EXPECT_TRUE(t.board.hp_reset);
  const int pulse = static_cast<int>(t.cfg.hp_reset_pulse_us / t.cfg.period_us);
  for (int i = 0; i < pulse; ++i) t.Step();
  EXPECT_FALSE(t.board.hp_reset);
  // Refused while the HP is flying: restarting it then would be a self-inflicted failure.
  ASSERT_GT(t.ReachHp(), 0);
  t.Operator(HA_OP_RESTART_HP);
  t.StepWithGood();
  EXPECT_EQ(t.app.requests.ack_accepted, 0u);
  EXPECT_EQ(t.controller(), HA_CONTROLLER_HP);
}

TEST(HaDecision, ClockWrapDoesNotLookLikeACrash) {
  Timeline t;
  t.board.now_us = 0xFFFFFFFFu - 3u * t.cfg.stable_window_us;
  ASSERT_GT(t.ReachHp(), 0);
  for (int i = 0; i < 1000; ++i) {
    t.StepWithGood();
    ASSERT_EQ(t.controller(), HA_CONTROLLER_HP) << "period " << i;
  }
  EXPECT_LT(t.board.now_us, 0x10000000u);  // it did wrap
}

// A dead INS stays dead: ages saturate, so 2^32 us later the last state is not fresh again.
TEST(HaDecision, InsSilentAcrossTheClockWrapStaysStale) {
  Timeline t;
  ASSERT_GT(t.ReachHp(), 0);
  t.refresh_state = false;  // the HA's INS feed dies for good; the HP keeps flying
  const uint64_t periods = (uint64_t{1} << 32) / t.cfg.period_us + 1000u;
  const uint64_t stale_after = t.cfg.state_timeout_us / t.cfg.period_us + 2u;
  for (uint64_t i = 0; i < periods; ++i) {
    t.StepWithGood();
    if (i > stale_after) {
      ASSERT_NE(t.controller(), HA_CONTROLLER_HP) << "period " << i << " of a dead INS";
      ASSERT_NE(t.out().reasons, 0u) << "period " << i;
    }
    if (i % 10000u == 0u) t.board.servo_writes.clear();  // 72 minutes of writes: keep it small
  }
  EXPECT_LT(t.board.now_us, 0x10000000u);  // it did wrap
}

// An INS that delivers every 150 ms, past state_timeout_s every other period: the HA cannot check
// the HP part of the time and holds the servos, instead of handing back on each fresh state
// (86 controller changes a minute with a healthy HP, issue 22 F10).
TEST(HaDecision, InsEvery150msDoesNotSwapTheControllerEveryFewPeriods) {
  Timeline t;
  ASSERT_GT(t.ReachHp(), 0);
  int hp_changes = 0;  // into or out of the HP's hands
  bool hp = true;
  for (int i = 0; i < 6000; ++i) {
    t.refresh_state = i % 15 == 0;
    t.StepWithGood();
    hp_changes += (t.controller() == HA_CONTROLLER_HP) != hp ? 1 : 0;
    hp = t.controller() == HA_CONTROLLER_HP;
  }
  EXPECT_EQ(hp_changes, 1);
  EXPECT_NE(t.controller(), HA_CONTROLLER_HP);
  EXPECT_EQ(t.out().restart_count, 0u);  // the HA's own sensor is no HP fault
  // The INS back at its rate: the HP earns control after the stable window.
  t.refresh_state = true;
  EXPECT_GT(t.ReachHp(), 0);
}

// Feeds the INS adapter one solution per period, the way the board layer does.
struct InsFeed {
  explicit InsFeed(Timeline* timeline) : t(timeline) {
    ha_ins_init(&ins);
    HaInsSample home{};
    home.has = HA_INS_HAS_REQUIRED | HA_INS_HAS_GPS_FIX;
    home.lat_deg = 45.0;
    home.lon_deg = -122.0;
    home.alt_m = 100.0;
    home.ins_status = 0x0006u;  // tracking, GNSS fix
    home.gps_fix = 3;
    // Home was latched on the ground, before this story starts: the core said so (1).
    ha_ins_update(&ins, &t->cfg, &home, 1u, t->board.now_us, &t->app.inputs);
    flying = home;
    flying.alt_m += 61.0;
    flying.lat_deg += 0.0011;  // about the circle's radius north of home
    flying.ypr_deg[0] = 90.0f;
    flying.vel_ned_mps[1] = 18.0f;
    t->refresh_state = false;
  }
  void Deliver(const HaInsSample& s) {
    ha_ins_update(&ins, &t->cfg, &s, t->app.outputs.on_ground,
                  t->board.now_us + t->cfg.period_us / 2u, &t->app.inputs);
  }
  Timeline* t;
  HaIns ins;
  HaInsSample flying;
};

TEST(HaDecision, OneRejectedInsPacketIsNotAnHpFault) {
  Timeline t;
  InsFeed feed(&t);
  for (int i = 0; i < 1000 && t.controller() != HA_CONTROLLER_HP; ++i) {
    feed.Deliver(feed.flying);
    t.StepWithGood();
  }
  ASSERT_EQ(t.controller(), HA_CONTROLLER_HP);
  // Four times within a minute, one packet with an INS error flag among good ones.
  for (int glitch_no = 0; glitch_no < 4; ++glitch_no) {
    HaInsSample glitch = feed.flying;
    glitch.ins_status |= 0x0010u;
    feed.Deliver(glitch);
    t.StepWithGood();
    for (int i = 0; i < 1500; ++i) {
      feed.Deliver(feed.flying);
      t.StepWithGood();
      ASSERT_EQ(t.controller(), HA_CONTROLLER_HP) << "glitch " << glitch_no << " period " << i;
    }
  }
  EXPECT_EQ(t.out().restart_count, 0u);
  EXPECT_EQ(t.board.hp_reset_assertions, 0);
}

TEST(HaDecision, OneFailedPitotReadIsNotAStallNorAnHpFault) {
  Timeline t;
  ASSERT_GT(t.ReachHp(), 0);
  for (int glitch_no = 0; glitch_no < 4; ++glitch_no) {  // four within a minute
    t.board.airspeed_ok = false;  // one I2C read fails: the core sees -1 ft/s
    t.StepWithGood();
    EXPECT_EQ(t.controller(), HA_CONTROLLER_HP) << "glitch " << glitch_no;
    EXPECT_EQ(t.out().reasons & HA_REASON_STALL, 0u) << "glitch " << glitch_no;
    t.board.airspeed_ok = true;
    for (int i = 0; i < 1500; ++i) t.StepWithGood();
    EXPECT_EQ(t.controller(), HA_CONTROLLER_HP);
  }
  EXPECT_EQ(t.out().restart_count, 0u);
  EXPECT_EQ(t.board.hp_reset_assertions, 0);
}

TEST(HaDecision, DeadPitotGivesTheHaControlWithoutResettingTheHp) {
  Timeline t;
  ASSERT_GT(t.ReachHp(), 0);
  t.board.airspeed_ok = false;  // the pitot is gone for good
  for (int i = 0; i < 500; ++i) t.StepWithGood();
  EXPECT_NE(t.controller(), HA_CONTROLLER_HP);  // nobody can check for a stall now
  EXPECT_EQ(t.out().reasons & HA_REASON_STALL, 0u);
  EXPECT_EQ(t.out().restart_count, 0u);
  EXPECT_EQ(t.board.hp_reset_assertions, 0);
  // The pitot comes back: the HP, which did nothing wrong, gets control back.
  t.board.airspeed_ok = true;
  EXPECT_GT(t.ReachHp(), 0);
  EXPECT_EQ(t.out().restart_count, 0u);
}

// Airborne is latched from more than height: a low pass keeps the motor and the stall check.
TEST(HaDecision, LowPassAtTwentyFiveFeetKeepsTheMotorAndTheStallCheck) {
  Timeline t;
  ASSERT_GT(t.ReachHp(), 0);
  t.Cruise(25.0f, 60.0f);  // the HP flies a low pass
  for (int i = 0; i < 100; ++i) t.StepWithGood();
  ASSERT_EQ(t.controller(), HA_CONTROLLER_HP);
  for (int i = 0; i < 300; ++i) t.Step();  // and dies there
  ASSERT_EQ(t.controller(), HA_CONTROLLER_HA);
  EXPECT_GT(t.servos().throttle, 0.5f * t.cfg.sc_throttle_trim);  // the motor keeps running
  t.board.airspeed_ftps = t.cfg.stall_speed_ftps - 4.0f;
  t.Step();
  EXPECT_TRUE(t.out().reasons & HA_REASON_STALL);
  // Below the launch point (terrain falls away), flying: the same.
  t.Cruise(-40.0f, 60.0f);
  for (int i = 0; i < 300; ++i) t.Step();
  EXPECT_GT(t.servos().throttle, 0.5f * t.cfg.sc_throttle_trim);
  // A landing is evident only once parked: then the motor idles and the stall check is off.
  t.Parked();
  for (int i = 0; i < 100 * 10; ++i) t.Step();
  EXPECT_FLOAT_EQ(t.servos().throttle, t.cfg.throttle_min);
  EXPECT_EQ(t.out().reasons & HA_REASON_STALL, 0u);
}

// An HP that fails while the pilot or the operator's HA flies is restarted all the same, once,
// and whoever flies keeps the servos throughout; handed back, the restarted HP earns control as
// usual. A failing HP that is alive (its sensor link lost) was never restarted while another flew
// (issue 22, F9). Each case: who holds the servos, and how the HP fails.
struct Holder {
  const char* name;
  uint8_t controller;
  void (*take)(Timeline*);
  void (*hand_back)(Timeline*);
};
struct HpFailure {
  const char* name;
  int periods;
  void (*period)(Timeline*);
};

const Holder kPilot = {"ThePilotFlies", HA_CONTROLLER_MANUAL,
                       [](Timeline* t) { t->board.SetPilotInCommand(true); },
                       [](Timeline* t) { t->board.SetPilotInCommand(false); }};
const Holder kOperatorHa = {"TheOperatorHoldsTheHa", HA_CONTROLLER_HA,
                            [](Timeline* t) { t->Operator(HA_OP_SELECT_HA); },
                            [](Timeline* t) { t->Operator(HA_OP_SELECT_HP); }};
const HpFailure kProcessDies = {"Dies", 100, [](Timeline* t) { t->Step(); }};
const HpFailure kSensorLinkLost = {"LosesItsSensorLink", 500, [](Timeline* t) {
                                     HaHpCommand c =
                                         MakeCommand(t->NextSeq(), 0.45f, -1.0f, 2.0f, 0.5f);
                                     c.sensor_links_healthy = 0u;
                                     SealCommand(&c);
                                     t->StepWith(c);
                                   }};

class HpFailsWhileAnotherFlies : public ::testing::TestWithParam<std::tuple<Holder, HpFailure>> {};

TEST_P(HpFailsWhileAnotherFlies, IsRestartedOnceAndEarnsControlBackWhenHandedBack) {
  const Holder& holder = std::get<0>(GetParam());
  const HpFailure& failure = std::get<1>(GetParam());
  Timeline t;
  ASSERT_GT(t.ReachHp(), 0);
  holder.take(&t);
  for (int i = 0; i < 100; ++i) t.StepWithGood();
  ASSERT_EQ(t.controller(), holder.controller);
  ASSERT_EQ(t.out().restart_count, 0u);
  for (int i = 0; i < failure.periods; ++i) {
    failure.period(&t);
    ASSERT_EQ(t.controller(), holder.controller);
  }
  EXPECT_EQ(t.out().restart_count, 1u);
  EXPECT_EQ(t.board.hp_reset_assertions, 1);
  for (int i = 0; i < 100; ++i) t.StepWithGood();  // it boots and runs healthy again
  holder.hand_back(&t);
  EXPECT_GT(t.ReachHp(), 0);
  EXPECT_EQ(t.out().restart_count, 1u);
}

INSTANTIATE_TEST_SUITE_P(HaDecision, HpFailsWhileAnotherFlies,
                         ::testing::Combine(::testing::Values(kPilot, kOperatorHa),
                                            ::testing::Values(kProcessDies, kSensorLinkLost)),
                         [](const ::testing::TestParamInfo<std::tuple<Holder, HpFailure>>& info) {
                           return std::string("Hp") + std::get<1>(info.param).name + "While" +
                                  std::get<0>(info.param).name;
                         });

// At power-up the HP's first commands say its estimator has not converged yet: it is booting,
// not failing, and is not restarted for it.
TEST(HaDecision, HpStillConvergingAtPowerUpIsNotRestarted) {
  Timeline t;
  for (int i = 0; i < 500; ++i) {
    HaHpCommand c = MakeCommand(t.NextSeq(), 0.45f, -1.0f, 2.0f, 0.5f);
    c.estimator_converged = 0u;
    SealCommand(&c);
    t.StepWith(c);
  }
  EXPECT_EQ(t.controller(), HA_CONTROLLER_HA);
  EXPECT_EQ(t.out().restart_count, 0u);
  EXPECT_GT(t.ReachHp(), 0);
}

// One reset pulse is one restart, however many reasons asked for it in that period.
TEST(HaDecision, OperatorRestartDuringAFailedRecoveryCountsOnce) {
  Timeline t;
  ASSERT_TRUE(HpFliesThenCrashes(&t));
  for (int i = 0; i < 50; ++i) t.Step();
  for (int i = 0; i < 20; ++i) t.StepWithGood();
  ASSERT_EQ(t.controller(), HA_CONTROLLER_RECOVERING);
  // In the same period: the operator asks for a restart and the HP fails its recovery.
  t.Operator(HA_OP_RESTART_HP);
  t.StepWithGood(0.0f, 2.0f * t.cfg.elevator_limit_deg);
  EXPECT_EQ(t.controller(), HA_CONTROLLER_HA);
  EXPECT_EQ(t.out().restart_requested, 1u);
  EXPECT_EQ(t.out().restart_count, 2u);
  EXPECT_EQ(t.board.hp_reset_assertions, 2);
}

// Airspeed hovering around stall: the HA keeps control until the HP could fly with margin.
TEST(HaDecision, AirspeedHoveringAtStallDoesNotCycleHpAndHa) {
  Timeline t;
  ASSERT_GT(t.ReachHp(), 0);
  int handbacks = 0;
  uint8_t before = t.controller();
  for (int i = 0; i < 100 * 120; ++i) {
    // 3 s just below stall, 3 s just above it, for two minutes.
    t.board.airspeed_ftps = t.cfg.stall_speed_ftps + ((i / 300) % 2 == 0 ? -1.0f : 1.0f);
    t.app.inputs.vel_east_ftps = t.app.inputs.groundspeed_ftps =
        t.board.airspeed_ftps;  // still air
    t.StepWithGood();
    if (t.controller() == HA_CONTROLLER_HP && before != HA_CONTROLLER_HP) ++handbacks;
    before = t.controller();
  }
  EXPECT_EQ(handbacks, 0);
  EXPECT_NE(t.controller(), HA_CONTROLLER_HA_LATCHED);
  EXPECT_EQ(t.out().restart_count, 1u);
  // With the margin regained the HP gets control back.
  t.board.airspeed_ftps = 60.0f;
  t.app.inputs.vel_east_ftps = t.app.inputs.groundspeed_ftps = t.board.airspeed_ftps;
  EXPECT_GT(t.ReachHp(), 0);
}

TEST(HaDecision, BoardIsServedEveryPeriod) {
  Timeline t;
  for (int i = 0; i < 10; ++i) t.StepWithGood();
  EXPECT_EQ(t.board.watchdog_kicks, 10u);
  EXPECT_EQ(t.board.servo_writes.size(), 10u);
  EXPECT_EQ(t.board.leds & (HA_LED_HA | HA_LED_FAULT), HA_LED_HA);  // recovering, no fault
}

}  // namespace

// The HiL's Fig. 5.3 plots the safety controller's own output next to the HP's: the core reports
// it every period, and it is what the HA flies once it takes over. (While the HP flies it tracks
// the applied surfaces wherever its back-calculated integrators can, for a bumpless takeover.)
TEST(HaDecision, SafetyControllerCommandIsReportedWhileTheHpFliesAndFlownAfterACrash) {
  Timeline t;
  t.Cruise();
  t.ReachHp();
  const HaOutputs& flying = t.StepWithGood(2.0f, -1.0f, 0.5f, 0.45f);
  ASSERT_EQ(HA_CONTROLLER_HP, flying.controller);
  EXPECT_TRUE(SurfacesFinite(flying.ha_command));
  EXPECT_TRUE(SurfacesInside(t.cfg, flying.ha_command));
  for (int k = 0; k < 200 && t.controller() == HA_CONTROLLER_HP; ++k) {
    t.Step();  // the HP is gone
  }
  ASSERT_EQ(HA_CONTROLLER_HA, t.controller());
  for (int k = 0; k < 300; ++k) {
    t.Step();  // past the bumpless slew
  }
  EXPECT_FLOAT_EQ(t.out().ha_command.aileron_deg, t.out().surfaces.aileron_deg);
  EXPECT_FLOAT_EQ(t.out().ha_command.elevator_deg, t.out().surfaces.elevator_deg);
}
