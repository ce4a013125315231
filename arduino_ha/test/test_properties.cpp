// Randomized property test of the whole core over millions of hostile inputs (NaN, +/-inf, huge,
// denormal, limit-hugging and plain garbage), seeded so every failure reproduces:
//   1. what goes to the servos is always finite and inside S_u;
//   2. an HP command outside S_u never reaches a servo (the HP is not in control with it);
//   3. every reported value is finite;
//   4. whenever the servos change hands (HP, HA incl. recovering and latched, pilot, self-test),
//      no surface moves faster than its configured rate limit until the new source's command is
//      reached: |delta| <= rate limit x period, in every period of the transition; except
//      to the pilot: in MANUAL the servos are exactly the pilot's sticks from the period of
//      the switch on (the pilot's inputs are never rate-limited).
// Episodes alternate between mostly sane and fully hostile inputs so that the HP really is in
// control often enough for property 2 to be exercised.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>

#include "ha_num.h"
#include "ha_surfaces.h"
#include "ha_test_util.h"

namespace {

class Hostile {
 public:
  explicit Hostile(uint64_t seed) : rng_(seed) {}

  bool Chance(double p) { return std::uniform_real_distribution<double>(0.0, 1.0)(rng_) < p; }
  uint32_t U32() { return static_cast<uint32_t>(rng_()); }
  float Uniform(float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(rng_); }

  float AnyFloat() {
    switch (rng_() % 9) {
      case 0:
        return std::numeric_limits<float>::quiet_NaN();
      case 1:
        return (rng_() & 1) ? std::numeric_limits<float>::infinity()
                            : -std::numeric_limits<float>::infinity();
      case 2:
        return ((rng_() & 1) ? 1.0f : -1.0f) * Uniform(1e30f, 3.4e38f);
      case 3:
        return ((rng_() & 1) ? 1.0f : -1.0f) * Uniform(1e-45f, 1e-38f);  // denormals
      case 4:
        return (rng_() & 1) ? 0.0f : -0.0f;
      case 5: {  // any bit pattern, signalling NaNs included
        const uint32_t bits = U32();
        float f;
        std::memcpy(&f, &bits, sizeof f);
        return f;
      }
      default:
        return Uniform(-1000.0f, 1000.0f);
    }
  }
  // A sane value most of the time, anything with probability p.
  float Maybe(double p, float sane) { return Chance(p) ? AnyFloat() : sane; }
  // Near a limit on either side: where off-by-one comparisons hide.
  float NearLimit(float limit) {
    return ((rng_() & 1) ? 1.0f : -1.0f) * limit * Uniform(0.95f, 1.05f);
  }
  // Near the limit or anything at all.
  float Beyond(float limit) { return Chance(0.5) ? NearLimit(limit) : AnyFloat(); }

 private:
  std::mt19937_64 rng_;
};

// Who drives the servos this period, as the core's choose_source() decides it.
enum class Source { kHa, kHp, kManual, kSelfTest };
Source SourceOf(const HaOutputs& out) {
  if (out.controller == HA_CONTROLLER_MANUAL) return Source::kManual;
  if (out.self_test_active) return Source::kSelfTest;
  if (out.controller == HA_CONTROLLER_HP) return Source::kHp;
  return Source::kHa;
}

// The rate limit is the bumpless-transfer limit (limits.yaml: "fastest a servo may be driven
// across a controller switch"), so property 4 is checked in every period of a transition, for
// every source on either side of it. Within one source's steady run it does not hold by design:
// the HP's accepted command passes bit for bit (property 2), the pilot's sticks pass straight
// through, and the safety controller's PID output is only saturated.
bool WithinRateLimit(const HaAircraftConfig& cfg, const HaSurfaces& before, const HaSurfaces& after,
                     uint32_t dt_us, bool ha_unloading_a_stall) {
  const double dt_s = dt_us * 1e-6;
  const double surface_step = cfg.surface_rate_limit_deg_per_s * dt_s + 1e-4;
  const double throttle_step = cfg.throttle_rate_limit_per_s * dt_s + 1e-6;
  // A pull (elevator negative) or a push (positive) may be eased towards neutral at the release
  // rate, not past it; the HA unloading a stall moves nose down at the release rate all the way.
  const double release_step = cfg.surface_release_rate_deg_per_s * dt_s + 1e-4;
  const double released = ha_unloading_a_stall ? before.elevator_deg + release_step
                                               : std::min(0.0, before.elevator_deg + release_step);
  const double elevator_up_to = std::max(double{before.elevator_deg} + surface_step, released);
  const double push_released = std::max(0.0, before.elevator_deg - release_step);
  const double elevator_down_to =
      std::min(double{before.elevator_deg} - surface_step, push_released);
  return double{after.elevator_deg} <= elevator_up_to &&
         double{after.elevator_deg} >= elevator_down_to &&
         std::fabs(double{after.aileron_deg} - before.aileron_deg) <= surface_step &&
         std::fabs(double{after.rudder_deg} - before.rudder_deg) <= surface_step &&
         std::fabs(double{after.throttle} - before.throttle) <= throttle_step;
}

TEST(HaProperties, ServosAlwaysFiniteInsideSuAndOutsideCommandsNeverReachThem) {
  const HaAircraftConfig& cfg = ha_aircraft_config;
  Hostile h(0x5eed1234u);
  const int kEpisodes = 1000;
  const int kStepsPerEpisode = 3000;  // 30 s of flight each: long enough to hand over to the HP
  uint64_t steps = 0, hp_steps = 0, outside_rejected = 0, rate_limited = 0, pilot_handed = 0;
  uint64_t handovers[4][4] = {};  // [from][to] source changes seen
  HaCore core;
  HaInputs in;
  HaOutputs out;
  for (int episode = 0; episode < kEpisodes; ++episode) {
    // Probability that any one input is hostile in this episode.
    const double kHostility[] = {1.0, 0.05, 0.002, 0.0002};
    const double p = kHostility[episode % 4];
    // Some mildly hostile episodes start parked, where the operator runs the self-test.
    const bool parked = episode % 8 == 6;
    ha_core_init(&core, &cfg);
    std::memset(&in, 0, sizeof in);
    std::memset(&out, 0, sizeof out);
    uint32_t now = h.U32();
    uint32_t seq = h.U32();
    Source source = Source::kHa;  // an initialized core holds the HA's idle surfaces
    for (int i = 0; i < kStepsPerEpisode; ++i, ++steps) {
      const uint32_t before_us = now;
      now += h.Chance(p) ? h.U32() % (10u * cfg.period_us) : cfg.period_us;
      // The period the core slews over: nominal at first, and bounded by the no-command timeout.
      const uint32_t dt_us =
          i == 0 ? cfg.period_us : std::min(now - before_us, cfg.no_command_timeout_us);
      // Aircraft state: cruise with noise, or garbage.
      in.airspeed_ftps = h.Maybe(p, parked ? h.Uniform(0.0f, 5.0f) : h.Uniform(50.0f, 70.0f));
      in.roll_deg = h.Maybe(p, h.Uniform(-10.0f, 10.0f));
      in.pitch_deg = h.Maybe(p, h.Uniform(-5.0f, 5.0f));
      in.heading_deg = h.Maybe(p, h.Uniform(-720.0f, 720.0f));
      in.p_deg_s = h.Maybe(p, parked ? h.Uniform(-1.0f, 1.0f) : h.Uniform(-5.0f, 5.0f));
      in.q_deg_s = h.Maybe(p, parked ? h.Uniform(-1.0f, 1.0f) : h.Uniform(-5.0f, 5.0f));
      in.r_deg_s = h.Maybe(p, parked ? h.Uniform(-1.0f, 1.0f) : h.Uniform(-5.0f, 5.0f));
      in.altitude_agl_ft = h.Maybe(p, parked ? h.Uniform(0.0f, 10.0f) : h.Uniform(100.0f, 250.0f));
      in.north_ft = h.Maybe(p, h.Uniform(-1000.0f, 1000.0f));
      in.east_ft = h.Maybe(p, h.Uniform(-1000.0f, 1000.0f));
      in.groundspeed_ftps = h.Maybe(p, parked ? h.Uniform(0.0f, 1.0f) : h.Uniform(50.0f, 70.0f));
      // The INS's velocity behind it, along the heading (still air: the pitot agrees within a
      // wind), unless either is garbage.
      const float track_rad = std::isfinite(in.heading_deg) ? in.heading_deg / 57.29578f : 0.0f;
      in.vel_north_ftps = h.Maybe(p, in.groundspeed_ftps * std::cos(track_rad));
      in.vel_east_ftps = h.Maybe(p, in.groundspeed_ftps * std::sin(track_rad));
      in.climb_ftps = h.Maybe(p, h.Uniform(-2.0f, 2.0f));
      in.altitude_msl_ft = h.Maybe(p, h.Uniform(0.0f, 8000.0f));
      in.on_ground = h.Chance(p) ? static_cast<uint8_t>(h.U32()) : (parked ? 1u : 0u);
      in.state_valid = h.Chance(p) ? static_cast<uint8_t>(h.U32()) : 1u;
      in.state_rx_us = h.Chance(p) ? h.U32() : now;
      (void)h.Maybe(p, 12.0f);  // was the battery's, which the core no longer takes: same draws
      for (int c = 0; c < HA_RC_CHANNELS; ++c) {
        in.rc.pulse_us[c] = static_cast<uint16_t>(h.Chance(p) ? h.U32() : 1000u + h.U32() % 400u);
      }
      in.rc.valid = h.Chance(p) ? static_cast<uint8_t>(h.U32()) : 1u;
      // The operator's request of this period (the firmware hands over one at most); the ids
      // are drawn still, so that a seed replays the runs it did before the queue left the core.
      in.operator_command = HA_OP_NONE;
      if (parked && i == 100) {  // before the HP has earned control: the self-test may run
        in.operator_command = HA_OP_SELF_TEST;
        (void)h.U32();
      } else if (h.Chance(p * 0.1)) {
        in.operator_command = static_cast<uint8_t>(h.U32() % 6u);
        (void)h.U32();
      }
      // The HP command: mostly valid and fresh; sometimes late, stale, corrupt or hostile.
      if (!h.Chance(p)) {
        // The elevator no more nose-up than the pull limit: a pull past it is refused airborne
        // (REASON_PULL), which would keep the HP out of control for most of the run.
        HaHpCommand c = MakeCommand(h.Chance(p) ? seq : ++seq, h.Uniform(0.0f, 1.0f),
                                    h.Uniform(-cfg.elevator_pull_limit_deg, 10.0f),
                                    h.Uniform(-10.0f, 10.0f), h.Uniform(-10.0f, 10.0f));
        if (h.Chance(p * 5.0)) {  // beyond S_u with a valid CRC: only the region check can stop it
          switch (h.U32() % 4u) {
            case 0:
              c.elevator_deg = h.Beyond(cfg.elevator_limit_deg);
              break;
            case 1:
              c.aileron_deg = h.Beyond(cfg.aileron_limit_deg);
              break;
            case 2:
              c.rudder_deg = h.Beyond(cfg.rudder_limit_deg);
              break;
            default:
              c.throttle = h.Chance(0.5) ? h.Uniform(-0.1f, 1.1f) : h.AnyFloat();
              break;
          }
          SealCommand(&c);
        }
        if (h.Chance(p)) {
          c.alpha_est_deg = h.AnyFloat();
          c.beta_est_deg = h.AnyFloat();
          c.estimator_converged = static_cast<uint8_t>(h.U32());
          c.sensor_links_healthy = static_cast<uint8_t>(h.U32());
          if (h.Chance(0.5)) SealCommand(&c);
        }
        ha_inputs_put_hp_command(&in, &c, h.Chance(p) ? h.U32() : now - cfg.period_us / 2u);
      }

      const HaSurfaces applied_before = core.applied;
      const bool was_in_transition = core.transition_active != 0u;
      ha_core_step(&core, &in, now, &out);

      const Source source_now = SourceOf(out);
      if (source_now == Source::kManual) {
        HaSurfaces sticks;
        ha_surfaces_from_rc(&cfg, &in.rc, &sticks);
        ASSERT_EQ(std::memcmp(&out.surfaces, &sticks, sizeof sticks), 0)
            << "episode " << episode << " step " << i << ": in MANUAL the servos are not the "
            << "pilot's sticks";
        pilot_handed += source != Source::kManual ? 1u : 0u;
      } else if (source_now != source || was_in_transition) {
        ASSERT_TRUE(WithinRateLimit(cfg, applied_before, out.surfaces, dt_us,
                                    source_now == Source::kHa && (out.reasons & HA_REASON_STALL)))
            << "episode " << episode << " step " << i << " from source " << static_cast<int>(source)
            << " to " << static_cast<int>(source_now) << " dt_us " << dt_us << " aileron "
            << applied_before.aileron_deg << " -> " << out.surfaces.aileron_deg << " elevator "
            << applied_before.elevator_deg << " -> " << out.surfaces.elevator_deg << " throttle "
            << applied_before.throttle << " -> " << out.surfaces.throttle;
        ++rate_limited;
        ++handovers[static_cast<int>(source)][static_cast<int>(source_now)];
      }
      source = source_now;
      ASSERT_TRUE(SurfacesInside(cfg, out.surfaces)) << "episode " << episode << " step " << i;
      const HaSurfaces cmd{in.hp_cmd.throttle, in.hp_cmd.elevator_deg, in.hp_cmd.aileron_deg,
                           in.hp_cmd.rudder_deg};
      const bool cmd_outside = in.hp_cmd_count > 0 && !SurfacesInside(cfg, cmd);
      if (cmd_outside) {
        ASSERT_NE(out.controller, HA_CONTROLLER_HP)
            << "episode " << episode << " step " << i << " command " << cmd.throttle << " "
            << cmd.elevator_deg << " " << cmd.aileron_deg << " " << cmd.rudder_deg << " region "
            << out.actuator_region_max;
        ++outside_rejected;
      }
      if (out.controller == HA_CONTROLLER_HP) {
        ++hp_steps;
        // Once the handover slew is over, the HP's command passes bit for bit: the checks
        // accepted exactly what the saturation leaves unchanged.
        if (!core.transition_active) {
          ASSERT_EQ(std::memcmp(&out.surfaces, &cmd, sizeof cmd), 0)
              << "episode " << episode << " step " << i;
        }
      }
      ASSERT_TRUE(std::isfinite(out.stable_for_s) && std::isfinite(out.airspeed_ftps) &&
                  std::isfinite(out.altitude_agl_ft) && std::isfinite(out.alpha_deg) &&
                  std::isfinite(out.beta_deg) && std::isfinite(out.state_region_max) &&
                  std::isfinite(out.actuator_region_max));
      ASSERT_LE(out.controller, HA_CONTROLLER_MANUAL);
    }
  }
  RecordProperty("steps", static_cast<int>(steps));
  std::printf(
      "steps: %llu, HP in control: %llu, outside-S_u commands rejected: %llu, "
      "rate-limited transition periods: %llu\n",
      static_cast<unsigned long long>(steps), static_cast<unsigned long long>(hp_steps),
      static_cast<unsigned long long>(outside_rejected),
      static_cast<unsigned long long>(rate_limited));
  // The property must have been exercised, not vacuously true.
  EXPECT_EQ(steps, static_cast<uint64_t>(kEpisodes) * kStepsPerEpisode);
  EXPECT_GT(hp_steps, steps / 10);
  EXPECT_GT(outside_rejected, 10000u);
  // Property 4 met every kind of handover, not just one.
  const int ha = static_cast<int>(Source::kHa), hp = static_cast<int>(Source::kHp),
            manual = static_cast<int>(Source::kManual);
  EXPECT_GT(rate_limited, steps / 100);
  EXPECT_GT(pilot_handed, 100u);  // handovers to the pilot, onto the sticks at once
  EXPECT_GT(handovers[ha][hp], 100u);
  EXPECT_GT(handovers[hp][ha], 100u);
  EXPECT_GT(handovers[manual][ha] + handovers[manual][hp], 100u);
  const int self_test = static_cast<int>(Source::kSelfTest);
  // Every self-test period is a slew. Fewer than before issue 13: one hostile sample that looks
  // like flight now latches airborne (no self-test) until landed_confirm_s of parked; fewer again
  // since a push is eased back at the release rate too (1,923 at this seed).
  EXPECT_GT(handovers[self_test][self_test], 1500u);
}

TEST(HaProperties, BitComparisonsGiveTheFloatComparisonsVerdicts) {
  // ha_in_range and ha_greater decide on the IEEE-754 bits; they must agree with the float
  // comparisons they replace, for every kind of value incl. +/-0, denormals, inf and NaN.
  Hostile h(0xc0ffeeu);
  const float kSpecial[] = {0.0f,
                            -0.0f,
                            1e-45f,
                            -1e-45f,
                            1.0f,
                            -1.0f,
                            3.4e38f,
                            -3.4e38f,
                            std::numeric_limits<float>::infinity(),
                            -std::numeric_limits<float>::infinity()};
  for (int i = 0; i < 2000000; ++i) {
    const float a = i < 100 ? kSpecial[i % 10] : h.AnyFloat();
    const float b = i < 100 ? kSpecial[i / 10] : (h.Chance(0.3) ? a : h.AnyFloat());
    float lo = h.Chance(0.5) ? h.Uniform(-100.0f, 100.0f) : (i % 2 ? -0.0f : 0.0f);
    float hi = h.Chance(0.1) ? lo : lo + h.Uniform(0.0f, 100.0f);
    if (h.Chance(0.05)) {
      lo = a;
      hi = a;
    }  // a bound exactly on the value
    if (!std::isnan(a) && !std::isnan(b)) {
      ASSERT_EQ(ha_greater(a, b) != 0, a > b) << a << " > " << b;
    }
    if (std::isfinite(lo) && std::isfinite(hi)) {
      ASSERT_EQ(ha_in_range(a, lo, hi) != 0, a >= lo && a <= hi)
          << lo << " <= " << a << " <= " << hi;
    }
  }
}

TEST(HaProperties, EveryRcPulseMapsLinearlyOntoSuAndClampsOutsideTheRange) {
  // All 65536 pulse widths against the mapping's definition: [min, max] us linearly onto
  // [-limit, +limit] (throttle onto [min, max]), clamped outside, exact at both ends.
  const HaAircraftConfig& cfg = ha_aircraft_config;
  const double span_us = cfg.rc_pulse_max_us - cfg.rc_pulse_min_us;
  for (uint32_t pulse = 0; pulse <= 0xFFFFu; ++pulse) {
    HaRcInputs rc{};
    for (int c = 0; c < HA_RC_CHANNELS; ++c) rc.pulse_us[c] = static_cast<uint16_t>(pulse);
    rc.valid = 1;
    HaSurfaces s;
    ha_surfaces_from_rc(&cfg, &rc, &s);
    const double above_min_us = static_cast<double>(pulse) - cfg.rc_pulse_min_us;
    const double f = std::min(1.0, std::max(0.0, above_min_us / span_us));
    ASSERT_TRUE(SurfacesInside(cfg, s)) << pulse;
    ASSERT_NEAR(s.elevator_deg, (2.0 * f - 1.0) * cfg.elevator_limit_deg, 1e-5) << pulse;
    ASSERT_NEAR(s.aileron_deg, (2.0 * f - 1.0) * cfg.aileron_limit_deg, 1e-5) << pulse;
    ASSERT_NEAR(s.rudder_deg, (2.0 * f - 1.0) * cfg.rudder_limit_deg, 1e-5) << pulse;
    ASSERT_NEAR(s.throttle, cfg.throttle_min + f * (cfg.throttle_max - cfg.throttle_min), 1e-6)
        << pulse;
    if (pulse <= cfg.rc_pulse_min_us || pulse >= cfg.rc_pulse_max_us) {
      const float sign = pulse <= cfg.rc_pulse_min_us ? -1.0f : 1.0f;
      ASSERT_EQ(s.aileron_deg, sign * cfg.aileron_limit_deg) << pulse;
      ASSERT_EQ(s.throttle, sign < 0 ? cfg.throttle_min : cfg.throttle_max) << pulse;
    }
  }
}

TEST(HaProperties, HostileBoardReadingsNeverReachServosAndWatchdogIsKicked) {
  // The same through ha_app_period: a board whose clock jumps and whose readings fail or lie.
  Hostile h(0xb0a4d5u);
  Timeline t;
  const int kPeriods = 300000;
  for (int i = 0; i < kPeriods; ++i) {
    const double p = (i / 3000) % 2 == 0 ? 0.3 : 0.001;
    t.board.airspeed_ftps = h.Maybe(p, h.Uniform(45.0f, 70.0f));
    t.board.airspeed_ok = !h.Chance(p);
    t.board.battery_v = h.Maybe(p, 12.0f);
    t.board.battery_ok = !h.Chance(p);
    for (int c = 0; c < HA_RC_CHANNELS; ++c) {
      t.board.rc.pulse_us[c] =
          static_cast<uint16_t>(h.Chance(p) ? h.U32() : 1000u + h.U32() % 1000u);
    }
    t.board.rc.valid = static_cast<uint8_t>(h.Chance(p) ? h.U32() : 1u);
    if (h.Chance(p)) t.board.now_us += h.U32();
    if (h.Chance(p)) {
      t.Step();
    } else {
      t.StepWithGood(h.Uniform(-10.0f, 10.0f), h.Uniform(-10.0f, 10.0f), 0.0f,
                     h.Uniform(0.0f, 1.0f));
    }
    ASSERT_TRUE(SurfacesInside(t.cfg, t.servos())) << "period " << i;
  }
  EXPECT_EQ(t.board.watchdog_kicks, static_cast<uint64_t>(kPeriods));
  EXPECT_EQ(t.board.servo_writes.size(), static_cast<size_t>(kPeriods));
}

}  // namespace
