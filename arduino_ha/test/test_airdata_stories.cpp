// The HA's own airspeed picture (ha_airdata.c), one story per finding of issue 22: a stall judged
// by the load factor and the angle of attack, not by the 1 g stall speed alone; the pitot judged
// against the INS from both sides through the air's density and a learnt wind; the HA flying on
// the INS less the wind when the pitot lies or is gone; and the generator holding the stall rows
// to the airframe and the sensor timeouts to what the rules need.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

extern "C" {
#include "ha_safety_ctrl.h"
}
#include "ha_test_util.h"
#include "limits_generator.h"

namespace {

constexpr float kDegPerRad = 57.29578f;

// The INS's view of a flight along heading 90 (east): speed over the ground, flight path, pitch.
void FlyEast(Timeline* t, float ground_ftps, float climb_ftps, float pitch_deg, float roll_deg) {
  HaInputs& in = t->app.inputs;
  in.heading_deg = 90.0f;
  in.vel_north_ftps = 0.0f;
  in.vel_east_ftps = ground_ftps;
  in.groundspeed_ftps = ground_ftps;
  in.climb_ftps = climb_ftps;
  in.pitch_deg = pitch_deg;
  in.roll_deg = roll_deg;
}

// The safety controller's view of a flight believed in every sensor: wings level at this height
// and speed, on the circle at its radius headed east.
HaStateView FlyingView(const HaAircraftConfig& cfg, float alt_agl_ft, float ias_ftps) {
  HaStateView v{};
  v.attitude_ok = v.altitude_ok = v.position_ok = v.airspeed_ok = v.speed_ok = 1u;
  v.speed_known = 1u;
  v.airborne = 1u;
  v.x[HA_X_ALT_AGL_FT] = alt_agl_ft;
  v.airspeed_ftps = v.ias_ftps = v.tas_ftps = ias_ftps;
  v.ias_sq = ias_ftps * ias_ftps;
  v.cos_bank = v.load_factor = v.lift_load_factor = 1.0f;
  v.north_ft = cfg.sc_circle_radius_ft;
  v.heading_north = 0.0f;
  v.heading_east = 1.0f;
  return v;
}

// Steps with a healthy HP until the HA takes the servos; returns the periods it took (-1: never).
int PeriodsUntilTakeover(Timeline* t, int max_periods) {
  for (int i = 1; i <= max_periods; ++i) {
    if (t->StepWithGood().controller != HA_CONTROLLER_HP) return i;
  }
  return -1;
}

// A second of the HP's good commands in the state set up: it still flies (and if not, why not).
::testing::AssertionResult HpStillFliesAfterASecond(Timeline* t) {
  for (int i = 0; i < 100; ++i) t->StepWithGood();
  if (t->controller() == HA_CONTROLLER_HP) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "the HA took over, reasons " << t->out().reasons;
}

// The HA takes the servos within max_periods of the HP's good commands, for STALL alone.
::testing::AssertionResult TakenOverForStallWithin(Timeline* t, int max_periods) {
  if (PeriodsUntilTakeover(t, max_periods) < 0) {
    return ::testing::AssertionFailure() << "left to the HP for " << max_periods << " periods";
  }
  if (t->out().reasons_at_switch != HA_REASON_STALL) {
    return ::testing::AssertionFailure() << "taken over for reasons " << t->out().reasons_at_switch;
  }
  return ::testing::AssertionSuccess();
}

// F1. A stalled glide at 48 ft/s, above the 1 g switch speed of 46.2, at 14 deg of angle of
// attack (pitch 2, flight path -12): the 1 g stall speed says nothing is wrong; the INS's pitch
// less flight path says the wing is stalled.
TEST(HaAirdataStories, StalledGlideAt14DegAlphaAbove1gSwitchSpeedIsTakenOver) {
  Timeline t;
  t.Cruise(150.0f, 60.0f);
  ASSERT_GT(t.ReachHp(), 0);
  const float v = 48.0f, gamma_deg = -12.0f;
  ASSERT_GT(v, t.cfg.stall_switch_airspeed_ftps);
  // First an ordinary glide at the same speed (alpha 5 deg): the HP keeps flying.
  t.board.airspeed_ftps = v;
  FlyEast(&t, v * std::cos(3.0f / kDegPerRad), v * std::sin(-3.0f / kDegPerRad), 2.0f, 0.0f);
  ASSERT_TRUE(HpStillFliesAfterASecond(&t));
  // Then the stalled one.
  FlyEast(&t, v * std::cos(gamma_deg / kDegPerRad), v * std::sin(gamma_deg / kDegPerRad), 2.0f,
          0.0f);
  const int periods = PeriodsUntilTakeover(&t, 300);
  ASSERT_GT(periods, 0) << "the HP kept a stalled glide for 3 s";
  EXPECT_LE(periods, 2);
  EXPECT_TRUE(t.out().reasons_at_switch & HA_REASON_STALL);
  EXPECT_EQ(t.out().restart_count, 1u);  // a stall is the HP's doing
}

// A level coordinated turn at this bank and speed: the body's pitch rate that turns the velocity,
// q = omega sin(bank) with omega = g tan(bank) / V (what the INS's gyros report in it).
void LevelTurn(Timeline* t, float v_ftps, float roll_deg) {
  const float phi = roll_deg / kDegPerRad;
  FlyEast(t, v_ftps, 0.0f, 2.0f, roll_deg);
  t->app.inputs.q_deg_s = 32.174f * std::tan(phi) * std::sin(phi) / v_ftps * kDegPerRad;
}

// F1. In a 50 deg bank the load factor is 1/cos(50) = 1.56 and the stall speed 1.25 x the 1 g
// one: 55 ft/s is below the banked switch speed (57.6) though well above the 1 g one (46.2).
TEST(HaAirdataStories, BankedTurnStallSpeedScalesWithLoadFactor) {
  Timeline t;
  t.Cruise(200.0f, 55.0f);
  ASSERT_GT(t.ReachHp(), 0);
  const float banked_switch_ftps =
      t.cfg.stall_switch_airspeed_ftps / std::sqrt(std::cos(50.0f / kDegPerRad));
  ASSERT_LT(55.0f, banked_switch_ftps);
  LevelTurn(&t, 55.0f, 30.0f);  // 30 deg: n = 1.15, switch at 49.6: still flying
  ASSERT_TRUE(HpStillFliesAfterASecond(&t));
  LevelTurn(&t, 55.0f, 50.0f);
  EXPECT_TRUE(TakenOverForStallWithin(&t, 300)) << "55 ft/s in a 50 deg bank";
}

// Wings level at 70 ft/s and 200 ft, far above the 1 g switch speed, the HP flying: where a pull
// starts from.
::testing::AssertionResult HpFliesWingsLevelAt70Ftps(Timeline* t) {
  t->Cruise(200.0f, 70.0f);
  if (t->ReachHp() <= 0) return ::testing::AssertionFailure() << "the HP never got control";
  FlyEast(t, 70.0f, 0.0f, 2.0f, 0.0f);
  return ::testing::AssertionSuccess();
}

// F1, the HiL's accelerated_stall: wings level at 70 ft/s, far above the 1 g switch speed, the HP
// pulls: a pitch rate of 40 deg/s turns the velocity at 1.5 g on top of gravity's 1, and the wing
// needs (70 / 42)^2 = 2.8 g worth of lift coefficient to stall. The gyros show the load before
// the wing reaches its stall: the HA takes the servos while the bank alone says 1 g.
TEST(HaAirdataStories, PullUpAt70FtpsIsJudgedByTheLoadFactorTheGyrosShow) {
  Timeline t;
  ASSERT_TRUE(HpFliesWingsLevelAt70Ftps(&t));
  t.app.inputs.q_deg_s = 20.0f;  // a brisk pitch-up: 0.76 g on top, 1.76 in all, not yet 2.45
  ASSERT_TRUE(HpStillFliesAfterASecond(&t));
  t.app.inputs.q_deg_s = 40.0f;  // 2.5 g: 70 ft/s is the switch speed x sqrt(2.5)
  EXPECT_TRUE(TakenOverForStallWithin(&t, 10)) << "a 2.5 g pull at 70 ft/s";
}

// HiL campaign seed 25 #94, moderate turbulence: the HP, pulling 4 deg inside the pull limit in
// a 27 deg bank, left the wing pitching up at 21 deg/s when the HA took over for STALL. The HA
// eased the pull out and then moved nose down at the bumpless rate, its pitch law still asking
// for height: the inherited pitch rate carried the wing 0.02 s past its stall. A stall is flown
// out as a pilot does: the nose down to the pitch limit, no pull held in the integrator, and the
// elevator moved nose down at the release rate, not eased.
TEST(HaAirdataStories, HpsPitchRateAtAStallTakeoverIsUnloadedAtOnceNotEasedOut) {
  Timeline t;
  ASSERT_TRUE(HpFliesWingsLevelAt70Ftps(&t));
  t.app.inputs.q_deg_s = 40.0f;  // 2.5 g at 70 ft/s: the switch speed x sqrt(2.5)
  int periods = 0;
  for (; periods < 10 && t.controller() == HA_CONTROLLER_HP; ++periods) {
    t.StepWithGood(2.0f, -4.0f);  // the HP's pull: inside elevator_pull_limit_deg
  }
  ASSERT_NE(t.controller(), HA_CONTROLLER_HP) << "a 2.5 g pull at 70 ft/s was left to the HP";
  ASSERT_EQ(t.out().reasons_at_switch, HA_REASON_STALL);
  const float at_takeover_deg = t.servos().elevator_deg;
  for (int i = 0; i < 4; ++i) t.Step();  // the wing still pitching up: still a stall
  ASSERT_TRUE(t.out().reasons & HA_REASON_STALL);
  const float bumpless_deg = 4.0f * t.cfg.surface_rate_limit_deg_per_s * t.cfg.period_us * 1e-6f;
  std::printf("STALL takeover: elevator %.2f -> %.2f deg (trailing edge down +) in 4 periods\n",
              at_takeover_deg, t.servos().elevator_deg);
  EXPECT_GT(t.servos().elevator_deg, 0.0f) << "the HP's pull still on a stalling wing";
  EXPECT_GT(t.servos().elevator_deg - at_takeover_deg, 2.0f * bumpless_deg)
      << "eased nose down at the bumpless rate";
}

// F2. The thesis's own stall signature: nose high, the pitot reading 12 ft/s (the relative wind
// far off its axis) while the INS sees 45 over the ground and the aircraft sinking. Not a lying
// pitot to be ignored: a stall, the HP reset, and the HA lowering the nose and opening the
// throttle.
TEST(HaAirdataStories, RealStallWithPitotFarBelowGroundspeedIsAStall) {
  Timeline t;
  t.Cruise(100.0f, 60.0f);
  ASSERT_GT(t.ReachHp(), 0);
  t.board.airspeed_ftps = 12.0f;
  FlyEast(&t, 45.0f, -8.0f, 16.0f, 0.0f);
  const int periods = PeriodsUntilTakeover(&t, 300);
  ASSERT_GT(periods, 0);
  EXPECT_TRUE(t.out().reasons_at_switch & HA_REASON_STALL) << t.out().reasons_at_switch;
  EXPECT_EQ(t.out().restart_count, 1u);
  EXPECT_GE(t.board.hp_reset_assertions, 1);
  for (int i = 0; i < 100; ++i) t.Step();  // the HP is being reset; past the handover slew
  EXPECT_GT(t.servos().elevator_deg, 0.0f) << "nose up in a stall";
  EXPECT_GT(t.servos().throttle, t.cfg.sc_throttle_trim);
}

// F2 downwind: after a minute in a 28 ft/s tailwind the HA knows the wind, so a pitot reading
// 37.6 at 68 over the ground is 40 ft/s through the air: believed, and a stall.
TEST(HaAirdataStories, RealStallInAKnownTailwindIsAStallNotALyingPitot) {
  Timeline t;
  t.Cruise(150.0f, 60.0f);
  FlyEast(&t, 88.0f, 0.0f, 2.0f, 0.0f);
  ASSERT_GT(t.ReachHp(), 0);
  for (int i = 0; i < 100 * 70; ++i) t.StepWithGood();
  ASSERT_EQ(t.controller(), HA_CONTROLLER_HP);
  t.board.airspeed_ftps = 37.6f;
  FlyEast(&t, 68.0f, -6.0f, 12.0f, 0.0f);
  EXPECT_TRUE(TakenOverForStallWithin(&t, 300));  // and not NO_HA_STATE: it is believed
}

// F3. The pitot stuck at 85 ft/s while the INS sees 35 over the ground in still air: 50 ft/s
// more than any wind explains. The HP flies on that pitot; the HA takes over.
TEST(HaAirdataStories, PitotStuckHighInStillAirIsRejected) {
  Timeline t;
  t.Cruise(150.0f, 60.0f);
  ASSERT_GT(t.ReachHp(), 0);
  t.board.airspeed_ftps = 85.0f;
  FlyEast(&t, 35.0f, 0.0f, 2.0f, 0.0f);
  const int periods = PeriodsUntilTakeover(&t, 300);
  ASSERT_GT(periods, 0) << "the HP kept flying on a pitot stuck 50 ft/s high";
  EXPECT_TRUE(t.out().reasons & HA_REASON_NO_HA_STATE);
  EXPECT_TRUE(t.out().reasons & HA_REASON_STALL);  // 35 ft/s through still air is a stall
  EXPECT_LT(t.out().airspeed_ftps, 85.0f);         // the 85 was never believed
}

// F3, the HiL's pitot_stuck story: iced at a reading 20 ft/s above the true 60, inside the 30 ft/s
// any wind could explain before the wind is known, so the two-sided test alone believes it for
// good and the HP, flying on the same pitot, slows towards the stall. A live sensor's noise moves
// every read; one repeated to the bit for pitot_stuck_s is stuck: the HA takes the servos then
// (its own airspeed lost, not an HP fault), and not one period earlier.
TEST(HaAirdataStories, PitotFrozenInsideTheWindToleranceIsDoubtedAfterPitotStuckS) {
  Timeline t;
  t.Cruise(200.0f, 60.0f);
  ASSERT_GT(t.ReachHp(), 0);
  t.board.airspeed_ftps = 80.0f;  // iced: it no longer moves
  t.board.pitot_noise = false;
  const int stuck_periods = static_cast<int>(t.cfg.pitot_stuck_us / t.cfg.period_us);
  const int periods = PeriodsUntilTakeover(&t, 3 * stuck_periods);
  ASSERT_GT(periods, 0) << "the HP kept flying on a pitot frozen at 80 ft/s";
  EXPECT_GE(periods, stuck_periods);
  EXPECT_LE(periods,
            stuck_periods + 2 + static_cast<int>(t.cfg.airspeed_timeout_us / t.cfg.period_us));
  EXPECT_EQ(t.out().reasons_at_switch & ~HA_REASON_STALL, HA_REASON_NO_HA_STATE);
  EXPECT_EQ(t.out().restart_count, 0u);
  // Still frozen minutes later: the HA keeps the servos and never hands them to an HP that flies
  // on that pitot.
  for (int i = 0; i < 6000; ++i) t.StepWithGood();
  EXPECT_NE(t.controller(), HA_CONTROLLER_HP);
}

// The same reading with a live sensor's noise on it is a wind, not a stuck pitot: the HP flies on.
TEST(HaAirdataStories, PitotReadingSteadilyHighWithItsNoiseIsNotStuck) {
  Timeline t;
  t.Cruise(200.0f, 60.0f);
  ASSERT_GT(t.ReachHp(), 0);
  t.board.airspeed_ftps = 80.0f;  // a 20 ft/s headwind, the groundspeed 60
  for (int i = 0; i < 1000; ++i) t.StepWithGood();
  EXPECT_EQ(t.controller(), HA_CONTROLLER_HP) << "reasons " << t.out().reasons;
}

// The HA's own pitch loop may not stall the wing: taking over an aircraft the HP left in a level
// 50 deg bank at 58 ft/s (1.56 g: 1.0 of the wing's maximum lift needs 42 x sqrt(1.56) = 52 ft/s)
// low in the band, the altitude term asks for the nose up, which would load the wing further;
// the lift guard (0.7 of the maximum: 1.33 g at 58 ft/s) pushes the nose down instead (HiL
// accelerated_stall: pitching up in the HP's 47 deg bank, the HA stalled the wing at 61 ft/s).
TEST(HaAirdataStories, HaInheritingASteepBankLowInTheBandPushesRatherThanLoadTheWing) {
  HaAircraftConfig cfg = ha_aircraft_config;
  HaStateView v = FlyingView(cfg, cfg.sc_alt_min_ft - 50.0f, 58.0f);
  v.alpha_ok = 1u;
  v.path_tas_sq = v.ias_sq;
  v.x[HA_X_ROLL_DEG] = 50.0f;
  v.cos_bank = std::cos(50.0f / kDegPerRad);
  v.load_factor = v.lift_load_factor = 1.0f / v.cos_bank;
  const HaSurfaces applied{};
  HaSurfaces guarded{}, unguarded{};
  HaSafetyCtrlState st{};
  ha_safety_ctrl_step(&st, &cfg, &v, &applied, 1, 0.01f, &guarded);
  EXPECT_GT(guarded.elevator_deg, 0.0f) << "trailing edge down: nose down";
  cfg.sc_lift_push_deg_per_g = 0.0f;  // the same law without the guard pulls
  HaSafetyCtrlState st2{};
  ha_safety_ctrl_step(&st2, &cfg, &v, &applied, 1, 0.01f, &unguarded);
  EXPECT_LT(unguarded.elevator_deg, 0.0f);
  // Wings level at 1 g, inside the guard: it does nothing.
  v.x[HA_X_ROLL_DEG] = 0.0f;
  v.cos_bank = v.load_factor = v.lift_load_factor = 1.0f;
  HaSurfaces level_guarded{}, level_unguarded{};
  HaSafetyCtrlState st3{}, st4{};
  ha_safety_ctrl_step(&st3, &cfg, &v, &applied, 1, 0.01f, &level_unguarded);
  cfg.sc_lift_push_deg_per_g = ha_aircraft_config.sc_lift_push_deg_per_g;
  ha_safety_ctrl_step(&st4, &cfg, &v, &applied, 1, 0.01f, &level_guarded);
  EXPECT_FLOAT_EQ(level_guarded.elevator_deg, level_unguarded.elevator_deg);
}

// HiL campaign seed 26 #91, moderate turbulence: the HP, flying a 33 deg bank with aileron held
// into it against the gusts, lost the servos; the HA's roll integrator, back-calculated to that
// aileron, held the bank for seconds (it unwinds at roll_ki, 0.4 deg/s at 8 deg of error) while
// the proportional term asked to roll out, and a gust stalled the banked wing at 75 ft. Past
// the bank limit no integrator holds the bank: the aileron rolls the wing out at once. Inside
// the limit the integrator is the loop's own, kept.
TEST(HaAirdataStories, AnInheritedSteepBankIsRolledOutAtOnceNotHeldByTheIntegrator) {
  const HaAircraftConfig& cfg = ha_aircraft_config;
  HaStateView v = FlyingView(cfg, 0.5f * (cfg.sc_alt_min_ft + cfg.sc_alt_max_ft), 65.0f);
  const auto fly = [&](float roll_deg, float hp_aileron_deg, int seconds) {
    // Headed 90 deg off the course, towards the side of the bank: the command is the limit.
    v.heading_north = roll_deg * cfg.sc_circle_direction > 0.0f ? 1.0f : -1.0f;
    v.heading_east = 0.0f;
    v.x[HA_X_ROLL_DEG] = roll_deg;
    v.cos_bank = std::cos(roll_deg / kDegPerRad);
    v.load_factor = v.lift_load_factor = 1.0f / v.cos_bank;
    HaSafetyCtrlState st{};
    HaSurfaces applied{}, out{};
    applied.aileron_deg = hp_aileron_deg;
    applied.throttle = cfg.sc_throttle_trim;
    ha_safety_ctrl_step(&st, &cfg, &v, &applied, 0, 0.01f, &out);  // tracking the HP
    float worst_into_bank_deg = -1e9f;
    for (int i = 0; i < seconds * 100; ++i) {
      ha_safety_ctrl_step(&st, &cfg, &v, &out, 1, 0.01f, &out);  // flying: the bank the gusts hold
      worst_into_bank_deg =
          std::max(worst_into_bank_deg, roll_deg > 0 ? out.aileron_deg : -out.aileron_deg);
    }
    return worst_into_bank_deg;
  };
  const float hold_deg = cfg.sc_integrator_authority * cfg.aileron_limit_deg;  // all it may hold
  const float bank_deg = cfg.sc_bank_limit_deg + 8.0f;
  EXPECT_LT(fly(bank_deg, hold_deg + 2.0f, 2), 0.0f) << "aileron into a bank past the limit";
  EXPECT_LT(fly(-bank_deg, -hold_deg - 2.0f, 2), 0.0f) << "aileron into a bank past the limit";
  // Inside the limit the integrator it tracked still trims the turn.
  EXPECT_GT(fly(20.0f, hold_deg, 1), fly(20.0f, 0.0f, 1) + 0.5f * hold_deg)
      << "the integrator dropped inside the bank limit";
}

// HiL campaigns, moderate turbulence: an updraft raises the angle of attack and the wing's load
// with no pitch rate. At 53 ft/s, wings level, the gyros say 1.0 g and the pitch loop, low in its
// band, pulls; the accelerometer says 1.6 g, past the 1.1 g the lift guard allows at that speed,
// and the HA pushes instead (HiL: the wing past its stall angle for up to 0.2 s, now 0.03).
TEST(HaAirdataStories, AGustsLoadTheGyrosCannotSeeIsPushedAgainst) {
  const HaAircraftConfig& cfg = ha_aircraft_config;
  HaStateView v = FlyingView(cfg, cfg.sc_alt_min_ft - 50.0f, 56.0f);
  v.x[HA_X_PITCH_DEG] = -3.0f;
  const HaSurfaces applied{};
  HaSurfaces calm{}, gust{};
  HaSafetyCtrlState st{}, st2{};
  v.lift_load_factor = 1.0f;  // what the gyros alone say
  ha_safety_ctrl_step(&st, &cfg, &v, &applied, 1, 0.01f, &calm);
  EXPECT_LT(calm.elevator_deg, 0.0f) << "low in the band and above the floor: nose up";
  v.accel_load_factor = v.lift_load_factor = 1.6f;
  ha_safety_ctrl_step(&st2, &cfg, &v, &applied, 1, 0.01f, &gust);
  EXPECT_GT(gust.elevator_deg, 0.0f) << "trailing edge down: nose down against the gust";
}

// ... and the accelerometer's load reaches the guard, never the stall check: a gust is the air's
// doing, not the HP's. 2 g at 60 ft/s with the HP flying straight and level (the gyros' 1 g)
// keeps the HP in control; the same 2 g pulled (the gyros' pitch rate) is a stall.
TEST(HaAirdataStories, AGustsLoadIsNotTheHpsStall) {
  Timeline t;
  t.Cruise(200.0f, 60.0f);
  ASSERT_GT(t.ReachHp(), 0);
  t.app.inputs.accel_ok = 1u;
  t.app.inputs.accel_load_factor = 2.0f;
  for (int i = 0; i < 20; ++i) t.StepWithGood();
  EXPECT_EQ(t.controller(), HA_CONTROLLER_HP) << "reasons " << t.out().reasons;
  t.app.inputs.q_deg_s = 32.174f / 60.0f * kDegPerRad;  // the same 2 g pulled by the HP
  EXPECT_TRUE(TakenOverForStallWithin(&t, 10));
}

// F7. The pitot dead from 30 ft, no wind ever learnt: the HA flies pitch and power, the nose no
// higher than the attitude that holds the speed and the throttle full below its band, so slow
// still beats low. Without a speed the pitch law held altitude alone and flew down to 44.2 ft/s.
TEST(HaAirdataStories, DeadPitotPitchLawKeepsAboveStall) {
  HaAloneFlight f;
  const HaAircraftConfig& cfg = f.cfg;
  PointMassAircraft& ac = f.ac;
  f.StartOnTheCircle(30.0f, 55.0f);
  float min_v = ac.airspeed_ftps, min_h = ac.altitude_ft;
  for (int i = 0; i < 100 * 120; ++i) {
    f.StepWithPitot(-1.0f);  // a failed read
    min_v = std::min(min_v, ac.airspeed_ftps);
    min_h = std::min(min_h, ac.altitude_ft);
  }
  std::printf("dead pitot from 30 ft, HA alone 120 s: lowest %.1f ft, slowest %.1f ft/s, %.0f ft\n",
              min_h, min_v, ac.altitude_ft);
  EXPECT_GT(min_v, cfg.stall_switch_airspeed_ftps);
  EXPECT_GT(min_h, 0.0f);
  EXPECT_GT(ac.altitude_ft, 30.0f);  // and it climbs towards its band
}

// Campaign flight 63 (seed 22): the pitot zeroed 9 s after the launch in a 15 ft/s wind, long
// before the wind is known. The HA flew the INS's speed over the ground, a believed 62 ft/s in
// the tailwind at a true 48, its throttle cut to 0.05 for the "excess" speed, and the wing
// stalled 2.7 s. With neither the pitot nor a known wind the HA knows no airspeed: it flies pitch
// and power, whose speed the wind does not change, round its circle through head- and tailwind.
TEST(HaAirdataStories, PitotZeroedBeforeTheWindIsKnownFliesPitchAndPowerNotGroundspeed) {
  HaAloneFlight f;
  const HaAircraftConfig& cfg = f.cfg;
  PointMassAircraft& ac = f.ac;
  f.StartOnTheCircle(0.5f * (cfg.sc_alt_min_ft + cfg.sc_alt_max_ft), 62.0f);
  ac.wind_east_ftps = 15.0f;  // blowing east: a tailwind along the first heading
  float min_v = ac.airspeed_ftps, min_throttle = 1.0f;
  for (int i = 0; i < 100 * 120; ++i) {            // three laps of the HA's circle
    const HaOutputs& out = f.StepWithPitot(0.0f);  // zeroed: reads, but nothing
    ASSERT_NE(out.controller, HA_CONTROLLER_HP);
    if (i > 100 * 5) {  // after the takeover's first seconds
      min_v = std::min(min_v, ac.airspeed_ftps);
      min_throttle = std::min(min_throttle, out.surfaces.throttle);
    }
  }
  std::printf(
      "pitot zeroed in a 15 ft/s wind, HA alone 120 s: slowest %.1f ft/s, throttle >= %.2f\n",
      min_v, min_throttle);
  EXPECT_GT(min_v, cfg.stall_speed_ftps * cfg.sc_stall_margin);
  EXPECT_GE(min_throttle, cfg.sc_throttle_trim - 0.01f) << "a tailwind's speed cut the power";
}

// The stall unload flies by a speed the HA may fly by. With the pitot zeroed before the wind is
// known, the checks judge by the INS's speed over the ground (the thesis's stall signature), and
// into a 28 ft/s headwind that is 38 ft/s at a true 66: STALL. Pushed to the pitch limit on it,
// the HA dived a healthy aircraft in every lap's upwind leg (pitch down to -6.5 deg, 146 ft from
// the band's middle of 200); it flies pitch and power instead.
TEST(HaAirdataStories, AHeadwindTheInsReadsAsAStallIsNotDivedIntoWithTheWindUnknown) {
  HaAloneFlight f;
  const HaAircraftConfig& cfg = f.cfg;
  PointMassAircraft& ac = f.ac;
  const float band_mid_ft = 0.5f * (cfg.sc_alt_min_ft + cfg.sc_alt_max_ft);
  f.StartOnTheCircle(band_mid_ft, 62.0f);
  ac.wind_east_ftps = 28.0f;
  ASSERT_LT(ac.wind_east_ftps, cfg.max_wind_ftps);
  float min_h = ac.altitude_ft, min_pitch = ac.pitch_deg;
  uint32_t stall_periods = 0u;
  for (int i = 0; i < 100 * 120; ++i) {
    const HaOutputs& out = f.StepWithPitot(0.0f);
    ASSERT_NE(out.controller, HA_CONTROLLER_HP);
    stall_periods += (out.reasons & HA_REASON_STALL) ? 1u : 0u;
    min_h = std::min(min_h, ac.altitude_ft);
    min_pitch = std::min(min_pitch, ac.pitch_deg);
  }
  std::printf(
      "pitot zeroed in a %.0f ft/s wind: %u periods of STALL, lowest %.1f ft, pitch >= %.1f\n",
      ac.wind_east_ftps, stall_periods, min_h, min_pitch);
  ASSERT_GT(stall_periods, 0u) << "the headwind never read as a stall: the story is not told";
  EXPECT_GT(min_h, cfg.sc_alt_min_ft - 20.0f);
  EXPECT_GT(min_pitch, -0.5f * cfg.sc_pitch_cmd_limit_deg);
}

// F8. A healthy pitot downwind at 6,500 ft: 60 ft/s indicated is 66.1 true there, and 94 over
// the ground is a 28 ft/s tailwind, inside max_wind. Compared as indicated airspeed against
// groundspeed (34 apart) it displaced a healthy HP.
TEST(HaAirdataStories, DownwindAtDensityAltitudeKeepsHealthyHp) {
  Timeline t;
  t.Cruise(200.0f, 60.0f);
  t.app.inputs.altitude_msl_ft = 6500.0f;
  FlyEast(&t, 94.0f, 0.0f, 2.0f, 0.0f);
  ASSERT_GT(t.ReachHp(), 0);
  uint32_t reasons_seen = 0u;
  for (int i = 0; i < 100 * 90; ++i) {
    reasons_seen |= t.StepWithGood().reasons;
    ASSERT_EQ(t.controller(), HA_CONTROLLER_HP) << "period " << i << " reasons " << t.out().reasons;
  }
  EXPECT_EQ(reasons_seen, 0u);
  // The same pitot at sea level would be 34 ft/s off the INS: a lie, not a tailwind.
  Timeline u;
  u.Cruise(200.0f, 60.0f);
  u.app.inputs.altitude_msl_ft = 200.0f;
  FlyEast(&u, 94.0f, 0.0f, 2.0f, 0.0f);
  EXPECT_LT(u.ReachHp(300), 0);
}

// ---- The generator ----

// G1. 4294.967295 s fits the 32-bit microsecond clock (2^32 - 1 us), and a dead INS or pitot
// would be trusted for 71 minutes. Every sensor timeout is refused past what the rules need.
TEST(HaAirdataStories, GeneratorRefusesUnboundedSensorTimeouts) {
  std::string err;
  ASSERT_EQ(GenerateWith("state_timeout_s", "0.1", &err), 0) << err;
  for (const char* key : {"state_timeout_s", "airspeed_timeout_s"}) {
    SCOPED_TRACE(key);
    ExpectRefused(key, "4294.967295", {key});
    ExpectRefused(key, "2.5", {key});  // past the 2 s stable window
  }
  // The pitot's hold may not outlast a 1 g deceleration through the stall inset (0.13 s).
  ExpectRefused("airspeed_timeout_s", "0.5", {"airspeed_timeout_s"});
}

// F1. One source for the stall: limits.yaml's stall alpha and stall speed are airframe.yaml's;
// the HP's estimate limit (divergence) may not lie inside the stall.
TEST(HaAirdataStories, GeneratorHoldsTheStallRowsToTheAirframe) {
  ExpectRefused("stall_alpha_deg", "12.0", {"stall_alpha_deg", "airframe.yaml"});
  ExpectRefused("alpha_limit_deg", "5.0", {"stall_alpha_deg"});
  ExpectRefused("stall_speed_ftps", "35.0", {"stall_speed_ftps"});
  EXPECT_LE(ha_aircraft_config.stall_alpha_deg, 8.85f);  // (cl_max - cl0) / cl_alpha
}

// Pitch and power's attitude must be one the pitch loop may command, and its throttle needs a
// band with a middle above its floor.
TEST(HaAirdataStories, GeneratorHoldsPitchAndPowerInsideThePitchLoopAndTheBand) {
  ExpectRefused("power_pitch_deg", "15.0", {"power_pitch_deg"});  // past pitch_cmd_limit_deg
  ExpectRefused("alt_max_ft", "150.0", {"alt_max_ft"});           // the band's floor itself
}

}  // namespace
