// The INS adapter (core/ha_ins.c): VN-200 solutions become the HA's aircraft state, in the
// core's units, relative to a home latched on the ground; anything the INS does not vouch for,
// or that is not a number, is dropped without stamping the state, which then ages out in the
// core (one bad packet is not a lost INS); before home is latched the state stays invalid.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "ha_aircraft.h"
#include "ha_ins.h"
#include "ha_test_util.h"

namespace {

constexpr double kHomeLatDeg = 45.0;
constexpr double kHomeLonDeg = -122.0;
constexpr double kHomeAltM = 100.0;
constexpr double kFtPerM = 1.0 / 0.3048;
// Reference lengths of one degree at 45 deg latitude on the WGS84 ellipsoid (published tables).
constexpr double kMPerDegLatAt45 = 111132.95;
constexpr double kMPerDegLonAt45 = 78846.84;
// INS status: mode tracking (2) with the GNSS fix bit.
constexpr uint16_t kTrackingWithFix = 0x0002u | 0x0004u;

HaInsSample Parked() {
  HaInsSample s{};
  s.has = HA_INS_HAS_REQUIRED | HA_INS_HAS_GPS_FIX;
  s.ypr_deg[0] = 10.0f;
  s.lat_deg = kHomeLatDeg;
  s.lon_deg = kHomeLonDeg;
  s.alt_m = kHomeAltM;
  s.ins_status = kTrackingWithFix;
  s.gps_fix = 3;
  return s;
}

HaInsSample Flying(double up_m, double north_deg, double east_deg) {
  HaInsSample s = Parked();
  s.lat_deg += north_deg;
  s.lon_deg += east_deg;
  s.alt_m += up_m;
  s.vel_ned_mps[0] = 25.0f;
  return s;
}

class InsAdapter : public ::testing::Test {
 protected:
  void SetUp() override { ha_ins_init(&ins); }
  int Update(const HaInsSample& s, uint32_t now_us) {
    return ha_ins_update(&ins, &ha_aircraft_config, &s, ha_on_ground, now_us, &in);
  }
  HaIns ins{};
  HaInputs in{};
  // The core's verdict (HaOutputs.on_ground): here it says on the ground, so the adapter's own
  // rules are what these tests see (test_ground_and_home.cpp goes through the core).
  uint8_t ha_on_ground = 1u;
};

// The accelerometer's z axis is the wing's load: -9.81 m/s^2 is 1 g of lift. It is optional (a
// Binary Output 1 saved before it was asked for leaves the load factor to the gyros) and a
// reading past the sensor's 16 g is no reading, while the rest of the solution stays good.
TEST_F(InsAdapter, AccelerometerZBecomesTheLoadFactorWhenThePacketCarriesIt) {
  ASSERT_EQ(Update(Parked(), 1000u), 1);
  HaInsSample s = Flying(50.0, 0.001, 0.0);
  ASSERT_EQ(Update(s, 2000u), 1);
  EXPECT_EQ(in.accel_ok, 0u);  // not in the packet
  s.has |= HA_INS_HAS_ACCEL;
  s.accel_mps2[2] = -1.5f * 9.80665f;  // a gust's 1.5 g
  ASSERT_EQ(Update(s, 3000u), 1);
  EXPECT_EQ(in.accel_ok, 1u);
  EXPECT_NEAR(in.accel_load_factor, 1.5f, 1e-4f);
  s.accel_mps2[2] = -200.0f;  // past the sensor's range
  ASSERT_EQ(Update(s, 4000u), 1);
  EXPECT_EQ(in.accel_ok, 0u);
  EXPECT_EQ(in.state_valid, 1u);
  s.accel_mps2[2] = std::numeric_limits<float>::quiet_NaN();
  ASSERT_EQ(Update(s, 5000u), 1);
  EXPECT_EQ(in.accel_ok, 0u);
}

TEST_F(InsAdapter, InsSolutionBecomesHaStateInHaUnits) {
  ASSERT_EQ(Update(Parked(), 1000u), 1);
  HaInsSample s = Flying(50.0, 0.001, 0.002);
  s.ypr_deg[0] = -135.0f;  // yaw
  s.ypr_deg[1] = 5.0f;     // pitch
  s.ypr_deg[2] = -20.0f;   // roll
  s.angular_rate_radps[0] = 0.5f;
  s.angular_rate_radps[1] = -0.25f;
  s.angular_rate_radps[2] = 1.0f;
  ASSERT_EQ(Update(s, 2000u), 1);
  EXPECT_EQ(in.state_valid, 1u);
  EXPECT_EQ(in.state_rx_us, 2000u);
  EXPECT_FLOAT_EQ(in.heading_deg, -135.0f);
  EXPECT_FLOAT_EQ(in.pitch_deg, 5.0f);
  EXPECT_FLOAT_EQ(in.roll_deg, -20.0f);
  EXPECT_NEAR(in.p_deg_s, 28.6479f, 1e-3f);
  EXPECT_NEAR(in.q_deg_s, -14.3239f, 1e-3f);
  EXPECT_NEAR(in.r_deg_s, 57.2958f, 1e-3f);
  EXPECT_NEAR(in.altitude_agl_ft, 50.0 * kFtPerM, 1e-2);
  EXPECT_NEAR(in.north_ft, 0.001 * kMPerDegLatAt45 * kFtPerM, 0.5);
  EXPECT_NEAR(in.east_ft, 0.002 * kMPerDegLonAt45 * kFtPerM, 0.5);
  EXPECT_NEAR(in.groundspeed_ftps, 25.0 * kFtPerM, 1e-3);
  EXPECT_EQ(in.on_ground, 0u);  // 25 m/s ground speed, 164 ft up
}

TEST_F(InsAdapter, ParkedAtHomeIsOnTheGroundAtZeroAltitude) {
  ASSERT_EQ(Update(Parked(), 10u), 1);
  EXPECT_EQ(in.on_ground, 1u);
  EXPECT_FLOAT_EQ(in.altitude_agl_ft, 0.0f);
  EXPECT_FLOAT_EQ(in.north_ft, 0.0f);
  EXPECT_FLOAT_EQ(in.east_ft, 0.0f);
}

TEST_F(InsAdapter, HomeLatchedAtFirstFixOnTheGround) {
  HaInsSample no_3d = Parked();
  no_3d.gps_fix = 2;
  no_3d.alt_m = 90.0;
  // Without a 3D fix no home: attitude and speed only (issue 22, F5: no longer no state at all).
  EXPECT_EQ(Update(no_3d, 10u), 1);
  EXPECT_EQ(in.state_valid, 1u);
  EXPECT_EQ(in.home_unknown, 1u);
  EXPECT_EQ(ins.home_latched, 0u);

  ASSERT_EQ(Update(Parked(), 20u), 1);  // first 3D fix on the ground: home at 100 m
  EXPECT_EQ(ins.home_latched, 1u);

  // Later parked fixes somewhere else do not move home.
  HaInsSample elsewhere = Parked();
  elsewhere.alt_m = kHomeAltM + 3.0;
  elsewhere.lat_deg += 0.0005;
  ASSERT_EQ(Update(elsewhere, 30u), 1);
  EXPECT_NEAR(in.altitude_agl_ft, 3.0 * kFtPerM, 1e-3);
  EXPECT_NEAR(in.north_ft, 0.0005 * kMPerDegLatAt45 * kFtPerM, 0.5);
}

TEST_F(InsAdapter, SetHomeOnTheGroundMovesHomeAndTheStateFollows) {
  ASSERT_EQ(Update(Parked(), 1000u), 1);
  EXPECT_EQ(ins.home_seq, 1u);
  // The operator puts home 0.001 deg north, 5 m higher.
  ASSERT_EQ(ha_ins_set_home(&ins, 1u, 0u, kHomeLatDeg + 0.001, kHomeLonDeg, kHomeAltM + 5.0),
            HA_INS_SET_HOME_OK);
  EXPECT_EQ(ins.home_seq, 2u);  // the link republishes it at once
  ASSERT_EQ(Update(Parked(), 3000u), 1);
  EXPECT_NEAR(in.north_ft, -0.001 * kMPerDegLatAt45 * kFtPerM, 0.5);
  EXPECT_NEAR(in.altitude_agl_ft, -5.0 * kFtPerM, 1e-3);
  // "Here": the last solution's position.
  HaInsSample moved = Parked();
  moved.lon_deg += 0.0002;
  ASSERT_EQ(Update(moved, 4000u), 1);
  ASSERT_EQ(ha_ins_set_home(&ins, 1u, 1u, 0.0, 0.0, 0.0), HA_INS_SET_HOME_OK);
  EXPECT_EQ(ins.home.lon_deg, kHomeLonDeg + 0.0002);
  EXPECT_EQ(ins.home.alt_m, kHomeAltM);
  ASSERT_EQ(Update(moved, 6000u), 1);
  EXPECT_NEAR(in.east_ft, 0.0, 1e-3);
}

TEST_F(InsAdapter, SetHomeInFlightIsRefusedAndHomeStays) {
  ASSERT_EQ(Update(Parked(), 1000u), 1);
  ASSERT_EQ(Update(Flying(60.0, 0.001, 0.0), 2000u), 1);
  EXPECT_EQ(ha_ins_set_home(&ins, 1u, 1u, 0.0, 0.0, 0.0), HA_INS_SET_HOME_NOT_ON_GROUND);
  EXPECT_EQ(ins.home_seq, 1u);
  EXPECT_EQ(ins.home.lat_deg, kHomeLatDeg);
  // Back on the ground but the core says no (its INS state timed out, or the pitot or the airborne
  // latch say flying): refused too.
  ASSERT_EQ(Update(Parked(), 4000u), 1);
  EXPECT_EQ(ha_ins_set_home(&ins, 0u, 1u, 0.0, 0.0, 0.0), HA_INS_SET_HOME_NOT_ON_GROUND);
  EXPECT_EQ(ins.home_seq, 1u);
}

TEST_F(InsAdapter, SetHomeBeforeAnyHomeOrToANonsensePositionIsRefused) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(ha_ins_set_home(&ins, 1u, 0u, kHomeLatDeg, kHomeLonDeg, kHomeAltM),
            HA_INS_SET_HOME_NOT_ON_GROUND);
  EXPECT_EQ(ins.home_latched, 0u);
  ASSERT_EQ(Update(Parked(), 1000u), 1);
  EXPECT_EQ(ha_ins_set_home(&ins, 1u, 0u, nan, kHomeLonDeg, kHomeAltM),
            HA_INS_SET_HOME_BAD_POSITION);
  EXPECT_EQ(ha_ins_set_home(&ins, 1u, 0u, kHomeLatDeg, 200.0, kHomeAltM),
            HA_INS_SET_HOME_BAD_POSITION);
  EXPECT_EQ(ha_ins_set_home(&ins, 1u, 0u, kHomeLatDeg, kHomeLonDeg, 1.0e6),
            HA_INS_SET_HOME_BAD_POSITION);
  EXPECT_EQ(ins.home_seq, 1u);
  EXPECT_EQ(ins.home.lat_deg, kHomeLatDeg);
}

TEST_F(InsAdapter, FirstFixInFlightDoesNotBecomeHome) {
  // Powered up in the air: no home, so no altitude AGL and no circle centre (the HA keeps
  // control) rather than circling wherever the fix happened. Attitude, rates and speed are
  // still the HA's (issue 22, F5: before, the whole state stayed invalid and the HA flew blind).
  EXPECT_EQ(Update(Flying(300.0, 0.0, 0.0), 10u), 1);
  EXPECT_EQ(ins.home_latched, 0u);
  EXPECT_EQ(in.state_valid, 1u);
  EXPECT_EQ(in.home_unknown, 1u);
  EXPECT_EQ(in.on_ground, 0u);
  HaInsSample climbing = Parked();
  climbing.vel_ned_mps[2] = -3.0f;  // slow over the ground but climbing: not parked either
  EXPECT_EQ(Update(climbing, 20u), 1);
  EXPECT_EQ(ins.home_latched, 0u);
}

TEST_F(InsAdapter, NanAttitudeIsDroppedUnstamped) {
  ASSERT_EQ(Update(Parked(), 10u), 1);
  HaInsSample s = Flying(30.0, 0.0, 0.0);
  s.ypr_deg[2] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(Update(s, 20u), 0);
  EXPECT_EQ(in.state_valid, 1u);       // the last good state stays, to age out in the core
  EXPECT_EQ(in.state_rx_us, 10u);      // not stamped
  EXPECT_FLOAT_EQ(in.roll_deg, 0.0f);  // not written
  EXPECT_FALSE(std::isnan(in.roll_deg));
  EXPECT_EQ(ins.solutions_rejected, 1u);

  // The next good solution makes it valid again.
  EXPECT_EQ(Update(Flying(30.0, 0.0, 0.0), 30u), 1);
  EXPECT_EQ(in.state_valid, 1u);
}

TEST_F(InsAdapter, NonFiniteOrImpossibleValuesAreRejected) {
  ASSERT_EQ(Update(Parked(), 10u), 1);
  const float inf = std::numeric_limits<float>::infinity();
  HaInsSample bad[6] = {Parked(), Parked(), Parked(), Parked(), Parked(), Parked()};
  bad[0].angular_rate_radps[1] = inf;
  bad[1].angular_rate_radps[2] = 100.0f;  // beyond the gyro's range
  bad[2].alt_m = std::numeric_limits<double>::quiet_NaN();
  bad[3].lat_deg = 91.0;
  bad[4].vel_ned_mps[0] = -inf;
  bad[5].ypr_deg[1] = 95.0f;  // pitch beyond +/-90
  for (const HaInsSample& s : bad) {
    EXPECT_EQ(Update(s, 20u), 0);
    EXPECT_EQ(in.state_rx_us, 10u);  // not stamped: the state ages from the last good one
  }
  EXPECT_EQ(ins.solutions_rejected, 6u);
}

TEST_F(InsAdapter, InsWithoutFixIsDroppedUnstamped) {
  ASSERT_EQ(Update(Parked(), 10u), 1);
  const uint16_t statuses[] = {
      0x0002u,                     // tracking, GNSS fix bit clear
      0x0001u | 0x0004u,           // aligning
      0x0003u | 0x0004u,           // GNSS lost for long: position dead-reckoned
      0x0000u,                     // not tracking
      kTrackingWithFix | 0x0010u,  // an error flag
  };
  for (uint16_t status : statuses) {
    HaInsSample s = Flying(30.0, 0.0, 0.0);
    s.ins_status = status;
    EXPECT_EQ(Update(s, 20u), 0) << "status " << status;
    EXPECT_EQ(in.state_rx_us, 10u) << "status " << status;
  }
}

TEST_F(InsAdapter, PacketWithoutAttitudeIsDroppedUnstamped) {
  ASSERT_EQ(Update(Parked(), 10u), 1);
  HaInsSample s = Flying(30.0, 0.0, 0.0);
  s.has = static_cast<uint8_t>(s.has & ~HA_INS_HAS_YPR);
  EXPECT_EQ(Update(s, 20u), 0);
  EXPECT_EQ(in.state_rx_us, 10u);
}

TEST_F(InsAdapter, CrossingTheAntimeridianIsAShortHop) {
  HaInsSample home = Parked();
  home.lon_deg = 179.9995;
  ASSERT_EQ(Update(home, 10u), 1);
  HaInsSample s = Flying(30.0, 0.0, 0.0);
  s.lon_deg = -179.9995;  // 0.001 deg east of home
  ASSERT_EQ(Update(s, 20u), 1);
  EXPECT_NEAR(in.east_ft, 0.001 * kMPerDegLonAt45 * kFtPerM, 0.5);
}

// End to end through the HA: without an INS state the HP never gets the servos; with the
// VN-200's solutions applied each period it does.
TEST(HaInsStory, Vn200SolutionsLetTheHpTakeControl) {
  for (const bool with_ins : {false, true}) {
    Timeline t;
    t.Cruise();
    t.refresh_state = false;
    t.app.inputs.state_valid = 0u;
    HaIns ins;
    ha_ins_init(&ins);
    HaInsSample home = Parked();
    // Home was latched on the ground, before this story starts: the core said so (1).
    ha_ins_update(&ins, &t.cfg, &home, 1u, t.board.now_us, &t.app.inputs);
    t.board.airspeed_ftps = 60.0f;
    bool hp_in_control = false;
    for (int i = 0; i < 1000 && !hp_in_control; ++i) {
      if (with_ins) {
        const HaInsSample s = Flying(61.0, 0.0, 0.0);
        ha_ins_update(&ins, &t.cfg, &s, t.app.outputs.on_ground,
                      t.board.now_us + t.cfg.period_us / 2u, &t.app.inputs);
      } else {
        t.app.inputs.state_valid = 0u;
      }
      t.StepWithGood();
      hp_in_control = t.controller() == HA_CONTROLLER_HP;
    }
    EXPECT_EQ(hp_in_control, with_ins) << (with_ins ? "with" : "without") << " INS";
  }
}

}  // namespace
