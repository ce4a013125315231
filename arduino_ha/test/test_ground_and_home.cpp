// On the ground is one rule (issue 22: F4, F5, F6, F11, K8, K9): the HA decides it once, from
// every sensor it has (the airborne latch, the pitot alive and below stall, a fresh INS parked and
// low), and the motor, the airborne latch, the first home and SET_HOME all follow it; and a reset
// of the HA in flight does not wake it on the ground.
#include <gtest/gtest.h>

#include <cmath>

#include "ha_aircraft.h"
#include "ha_ins.h"
#include "ha_retained.h"
#include "ha_test_util.h"

namespace {

constexpr double kHomeLatDeg = 45.0;
constexpr double kHomeLonDeg = -122.0;
constexpr double kHomeAltM = 100.0;
constexpr double kMPerFt = 0.3048;

HaInsSample AtHome() {
  HaInsSample s{};
  s.has = HA_INS_HAS_REQUIRED | HA_INS_HAS_GPS_FIX;
  s.lat_deg = kHomeLatDeg;
  s.lon_deg = kHomeLonDeg;
  s.alt_m = kHomeAltM;
  s.ins_status = 0x0006u;  // tracking, GNSS fix
  s.gps_fix = 3;
  return s;
}

// Level, heading north at this groundspeed, this high above home, this far north of it.
HaInsSample Level(double up_ft, double north_deg, float groundspeed_ftps) {
  HaInsSample s = AtHome();
  s.alt_m += up_ft * kMPerFt;
  s.lat_deg += north_deg;
  s.vel_ned_mps[0] = groundspeed_ftps * static_cast<float>(kMPerFt);
  return s;
}

// The HA as the firmware runs it: the Timeline's board and core, the INS adapter fed one solution
// per period with the core's latest verdict (as ha_vn200_feed_bytes is), the retained words
// restored at start-up (as due_main_setup does).
struct Ha {
  Ha() {
    t.refresh_state = false;  // the adapter stamps the state
    t.app.inputs.state_valid = 0u;
    ha_ins_init(&ins);
    ha_app_restore(&t.app, &t.board.iface, &ins);
  }
  // A watchdog or brown-out reset: RAM starts afresh, the board's retained words stay.
  void Reset() {
    ha_app_init(&t.app, &t.cfg);
    ha_ins_init(&ins);
    ha_app_restore(&t.app, &t.board.iface, &ins);
  }
  void Deliver(const HaInsSample& s) {
    ha_ins_update(&ins, &t.cfg, &s, t.app.outputs.on_ground, t.board.now_us + t.cfg.period_us / 2u,
                  &t.app.inputs);
  }
  // Periods with this solution and pitot reading (with_hp: a good HP command each period).
  void Run(int periods, const HaInsSample& s, float airspeed_ftps, bool with_hp = true) {
    t.board.airspeed_ftps = airspeed_ftps;
    for (int i = 0; i < periods; ++i) {
      Deliver(s);
      if (with_hp) {
        t.StepWithGood();
      } else {
        t.Step();
      }
    }
  }
  // Parked at home with the pitot reading still air: home latches.
  void LatchHomeOnTheGround() {
    Run(100, AtHome(), 0.0f, false);
    ASSERT_EQ(ins.home_latched, 1u);
    ASSERT_EQ(t.out().on_ground, 1u);
  }
  Timeline t;
  HaIns ins;
};

// F4: 20 ft up at 55 ft/s into a 20 ft/s headwind the INS calls the aircraft parked (35 ft/s over
// the ground, below the 42 ft/s stall, level, under 30 ft). Then the pitot dies. It used to clear
// the airborne latch 3 s later: the motor idled in flight and the stall check went off. A dead
// pitot is no evidence of a landing.
TEST(GroundAndHome, DeadPitotLowIntoHeadwindKeepsAirborneLatch) {
  Timeline t;
  t.Cruise(200.0f, 60.0f);
  ASSERT_GT(t.ReachHp(), 0);
  t.Cruise(20.0f, 55.0f);
  t.app.inputs.groundspeed_ftps = 35.0f;
  t.app.inputs.on_ground = 1u;  // what the INS adapter reports: parked and low
  for (int i = 0; i < 100; ++i) t.StepWithGood();
  ASSERT_EQ(t.app.core.airborne, 1u);
  t.board.airspeed_ok = false;
  for (int i = 0; i < 100 * 10; ++i) {
    t.StepWithGood();
    ASSERT_EQ(t.app.core.airborne, 1u) << "period " << i;
  }
  // The HA flies, knows it lacks its airspeed, and keeps the motor running.
  EXPECT_NE(t.controller(), HA_CONTROLLER_HP);
  EXPECT_TRUE(t.out().reasons & HA_REASON_NO_HA_STATE);
  EXPECT_EQ(t.out().on_ground, 0u);
  EXPECT_GT(t.servos().throttle, 0.9f * t.cfg.sc_throttle_trim);
}

// F6: power-up with a dead pitot and no GNSS fix yet (no INS state), with the receiver on in CIC
// or off: the motor used to spin up to the trim (0.40) on the ground, "blind counts as airborne".
// Power-up is on the ground until a sign of flight.
TEST(GroundAndHome, PowerUpBlindOnGroundKeepsMotorIdle) {
  for (const bool rc_on : {true, false}) {
    Ha ha;
    Timeline& t = ha.t;
    t.board.rc.valid = rc_on ? 1u : 0u;
    t.board.airspeed_ok = false;
    for (int i = 0; i < 100 * 10; ++i) {
      t.Step();
      ASSERT_FLOAT_EQ(t.servos().throttle, t.cfg.throttle_min) << "rc " << rc_on << " period " << i;
    }
    EXPECT_EQ(t.app.core.airborne, 0u);
    EXPECT_EQ(t.out().on_ground, 0u);  // it cannot vouch for the ground: no home, no SET_HOME
    // The fix and the pitot come: still on the ground, still idle, and home latches.
    t.board.airspeed_ok = true;
    ha.Run(100 * 5, AtHome(), 0.0f, false);
    EXPECT_FLOAT_EQ(t.servos().throttle, t.cfg.throttle_min);
    EXPECT_EQ(ha.ins.home_latched, 1u);
    // A sign of flight (the pitot above stall on the take-off run): the motor is the HA's again.
    ha.Run(100 * 3, Level(0.0, 0.0, 50.0f), 55.0f, false);
    EXPECT_EQ(t.app.core.airborne, 1u);
    EXPECT_GT(t.servos().throttle, t.cfg.throttle_min);
  }
}

// F5: a watchdog or brown-out reset in flight. Home could only latch on the ground, so every
// solution was refused afterwards: the healthy HP was locked out and the HA flew blind. The board
// keeps home and the airborne latch in its retained words; after the reset the HA takes them back,
// has its state at once, and hands the servos back to the HP.
TEST(GroundAndHome, ResetInFlightRestoresHomeAndHandsBackToHp) {
  Ha ha;
  Timeline& t = ha.t;
  ha.LatchHomeOnTheGround();
  const HaInsSample cruise = Level(200.0, 0.0011, 60.0f);
  ha.Run(100, cruise, 60.0f);
  for (int i = 0; i < 1000 && t.controller() != HA_CONTROLLER_HP; ++i) ha.Run(1, cruise, 60.0f);
  ASSERT_EQ(t.controller(), HA_CONTROLLER_HP);
  const GeoRef home = ha.ins.home;
  const uint32_t home_seq = ha.ins.home_seq;
  ASSERT_GT(t.board.retained_writes, 0u);

  ha.Reset();
  EXPECT_EQ(ha.ins.home_latched, 1u);
  EXPECT_NEAR(ha.ins.home.lat_deg, home.lat_deg, 1e-7);
  EXPECT_NEAR(ha.ins.home.lon_deg, home.lon_deg, 1e-7);
  EXPECT_NEAR(ha.ins.home.alt_m, home.alt_m, 1e-3);
  EXPECT_EQ(ha.ins.home_seq, home_seq);  // the link republishes the same home
  EXPECT_EQ(t.app.core.airborne, 1u);

  ha.Run(1, cruise, 60.0f);
  EXPECT_EQ(t.app.inputs.home_unknown, 0u);
  EXPECT_NEAR(t.app.inputs.altitude_agl_ft, 200.0f, 0.1f);  // not 0: home is where it was
  int back = 0;
  for (; back < 1000 && t.controller() != HA_CONTROLLER_HP; ++back) ha.Run(1, cruise, 60.0f);
  EXPECT_EQ(t.controller(), HA_CONTROLLER_HP);
  // The stable window and the rate-limited handover, no more (no restart, no boot wait).
  EXPECT_LE(back, static_cast<int>(t.cfg.stable_window_us / t.cfg.period_us) + 20);
  EXPECT_EQ(t.out().restart_count, 0u);
}

// A power-up is not a reset: what the backup registers hold then (zero, random bits, a record of
// another layout, a torn write) is no record, and the HA starts on the ground without home.
TEST(GroundAndHome, RetainedWordsWithoutAGoodRecordAreAPowerUp) {
  HaRetained r{};
  r.airborne = 1u;
  r.home_latched = 1u;
  r.home_lat_deg = kHomeLatDeg;
  r.home_lon_deg = kHomeLonDeg;
  r.home_alt_m = kHomeAltM;
  r.home_seq = 3u;
  uint32_t good[HA_RETAINED_WORDS];
  ha_retained_pack(&r, good);
  HaRetained back{};
  ASSERT_EQ(ha_retained_unpack(good, &back), 1);
  EXPECT_EQ(back.airborne, 1u);
  EXPECT_EQ(back.home_seq, 3u);
  for (uint32_t word = 0; word < HA_RETAINED_WORDS; ++word) {
    for (uint32_t bit = 0; bit < 32u; ++bit) {
      uint32_t flipped[HA_RETAINED_WORDS];
      for (uint32_t i = 0; i < HA_RETAINED_WORDS; ++i) flipped[i] = good[i];
      flipped[word] ^= 1u << bit;
      ASSERT_EQ(ha_retained_unpack(flipped, &back), 0) << "word " << word << " bit " << bit;
      ASSERT_EQ(back.airborne, 0u);
      ASSERT_EQ(back.home_latched, 0u);
    }
  }
  Ha ha;  // backup registers all zero
  EXPECT_EQ(ha.ins.home_latched, 0u);
  EXPECT_EQ(ha.t.app.core.airborne, 0u);
}

// A board without backup registers (a port that offers none: its read and write are NULL), or
// whose read fails, runs all the same, and a reset is a power-up: on the ground, without home.
TEST(GroundAndHome, ABoardWithoutRetainedWordsOrAFailingReadWakesAsAtPowerUp) {
  for (const bool failing_read : {false, true}) {
    SCOPED_TRACE(failing_read ? "the read fails" : "no retained words");
    Ha ha;
    if (failing_read) {
      ha.t.board.iface.read_retained = [](void*, uint32_t*) { return 0; };
    } else {
      ha.t.board.iface.read_retained = nullptr;
      ha.t.board.iface.write_retained = nullptr;
    }
    ha.LatchHomeOnTheGround();
    ha.Run(200, Level(200.0, 0.0011, 60.0f), 60.0f);
    ASSERT_EQ(ha.t.app.core.airborne, 1u);
    if (failing_read) {
      EXPECT_GT(ha.t.board.retained_writes, 0u);  // written all the same: a later read may work
    } else {
      EXPECT_EQ(ha.t.board.retained_writes, 0u);
    }
    ha.Reset();
    EXPECT_EQ(ha.ins.home_latched, 0u);
    EXPECT_EQ(ha.t.app.core.airborne, 0u);
  }
}

// The HA's own latches are kept too: an HA latched at the restart cap stays latched, and the
// operator's HA selection stands, across a reset (only a power cycle clears them).
TEST(GroundAndHome, ResetKeepsTheRestartCapLatchAndTheOperatorsChoice) {
  for (const bool latch : {true, false}) {
    Timeline t;
    HaIns ins;
    ha_ins_init(&ins);
    ha_app_restore(&t.app, &t.board.iface, &ins);
    if (latch) {
      for (uint32_t crash = 0; crash <= t.cfg.max_restarts; ++crash) {
        ASSERT_GT(t.ReachHp(), 0);
        t.Step();
        t.Step();
        for (int i = 0; i < 20; ++i) t.Step();
      }
      ASSERT_EQ(t.controller(), HA_CONTROLLER_HA_LATCHED);
    } else {
      ASSERT_GT(t.ReachHp(), 0);
      t.Operator(HA_OP_SELECT_HA);
      t.StepWithGood();
      ASSERT_EQ(t.controller(), HA_CONTROLLER_HA);
    }
    ha_app_init(&t.app, &t.cfg);  // the reset
    ha_ins_init(&ins);
    ha_app_restore(&t.app, &t.board.iface, &ins);
    t.Cruise();
    for (int i = 0; i < 1000; ++i) t.StepWithGood();
    EXPECT_EQ(t.controller(), latch ? HA_CONTROLLER_HA_LATCHED : HA_CONTROLLER_HA);
    EXPECT_EQ(t.out().reasons & HA_REASON_GROUND_COMMAND, latch ? 0u : HA_REASON_GROUND_COMMAND);
  }
}

// K8: 20 ft up at 70 ft/s airspeed into a 30 ft/s headwind, the INS alone calls it parked (40 ft/s
// over the ground, level, under 30 ft). A SET_HOME there moved home 1.1 km and 100 m up; the
// height then read -308 ft. The core's one rule says flying: refused, home stays.
TEST(GroundAndHome, SetHomeInFlightIntoHeadwindIsRefused) {
  Ha ha;
  ha.LatchHomeOnTheGround();
  const HaInsSample low_into_wind = Level(20.0, 0.01, 40.0f);  // 1.1 km north of home
  ha.Run(300, low_into_wind, 70.0f);
  ASSERT_EQ(ha.t.app.inputs.on_ground, 1u);  // the INS's own opinion
  const GeoRef home = ha.ins.home;
  EXPECT_EQ(ha_ins_set_home(&ha.ins, ha.t.app.outputs.on_ground, 1u, 0.0, 0.0, 0.0),
            HA_INS_SET_HOME_NOT_ON_GROUND);
  EXPECT_EQ(ha_ins_set_home(&ha.ins, ha.t.app.outputs.on_ground, 0u, kHomeLatDeg + 0.01,
                            kHomeLonDeg, kHomeAltM + 100.0),
            HA_INS_SET_HOME_NOT_ON_GROUND);
  EXPECT_EQ(ha.ins.home.lat_deg, home.lat_deg);
  EXPECT_EQ(ha.ins.home.alt_m, home.alt_m);
  EXPECT_EQ(ha.ins.home_seq, 1u);
  // Landed and parked there (pitot still, INS parked, for landed_confirm_s): now it may move.
  ha.Run(100 * 4, Level(0.0, 0.01, 0.0f), 0.0f);
  EXPECT_EQ(ha_ins_set_home(&ha.ins, ha.t.app.outputs.on_ground, 1u, 0.0, 0.0, 0.0),
            HA_INS_SET_HOME_OK);
  EXPECT_EQ(ha.ins.home_seq, 2u);
}

// K9: the INS first reports tracking in the air (its heading was still aligning on the ground),
// on a level leg into a headwind at 300 ft: slow over the ground and level, "parked" to the INS.
// Home latched there and the height read 0 ft (the ceiling and the circle moved with it). The
// core's rule says no: the pitot above stall is flying, a dead pitot vouches for nothing, and
// even a pitot reading below stall (a part-blocked tube) is not enough before home, when the INS
// has no height to tell: it must be still (stopped over the ground), which no flight is. The HA
// keeps its attitude and speed meanwhile.
TEST(GroundAndHome, FirstHomeNeverLatchesInFlight) {
  const HaInsSample leg = Level(300.0, 0.0, 30.0f);
  struct Pitot {
    bool alive;
    float ftps;
  };
  for (const Pitot pitot : {Pitot{true, 60.0f}, Pitot{false, 60.0f}, Pitot{true, 30.0f}}) {
    Ha ha;
    ha.t.board.airspeed_ok = pitot.alive;
    ha.Run(100 * 20, leg, pitot.ftps);
    EXPECT_EQ(ha.ins.home_latched, 0u) << "pitot " << pitot.alive << " " << pitot.ftps;
    EXPECT_EQ(ha.t.app.inputs.home_unknown, 1u);
    EXPECT_EQ(ha.t.app.inputs.on_ground, 1u);  // the INS's own opinion
    EXPECT_EQ(ha.t.out().on_ground, 0u);
    EXPECT_NE(ha.t.controller(), HA_CONTROLLER_HP);
    EXPECT_TRUE(ha.t.out().reasons & HA_REASON_NO_HA_STATE);
  }
}

// F11: SET_HOME's freshness was a wrapping difference of two clock readings: 2^32 us (71.6 min)
// after the last solution it read as fresh again. The core's state age saturates, and SET_HOME
// takes freshness from the core's verdict.
TEST(GroundAndHome, SetHomeFreshnessDoesNotWrap) {
  Ha ha;
  Timeline& t = ha.t;
  ha.LatchHomeOnTheGround();
  const uint32_t last_used_us = ha.ins.last_used_us;
  // The INS falls silent on the ground; the HA keeps running for 2^32 us.
  for (int i = 0; i < 64; ++i) {
    t.board.now_us += (1u << 26) - t.cfg.period_us;
    t.Step();
  }
  ASSERT_EQ(static_cast<uint32_t>(t.board.now_us - last_used_us), t.cfg.period_us / 2u);
  EXPECT_EQ(t.out().on_ground, 0u);
  EXPECT_EQ(ha_ins_set_home(&ha.ins, t.app.outputs.on_ground, 1u, 0.0, 0.0, 0.0),
            HA_INS_SET_HOME_NOT_ON_GROUND);
  EXPECT_EQ(ha.ins.home_seq, 1u);
}

}  // namespace
