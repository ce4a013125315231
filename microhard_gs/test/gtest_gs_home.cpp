// Home in the ground station: taken only from its owner, the HA (/home), sent as HOME_POSITION
// when it arrives or moves, and MAV_CMD_DO_SET_HOME forwarded to the HA on the ground and
// refused in flight with the reason.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "gs_core.h"
#include "gs_test_config.h"
#include "gs_test_frames.h"
#include "home_vectors.h"

using namespace microhard_gs;

namespace {

const GeoPoint kHaHome{40.4237054, -86.9211946, 185.25};

GsConfig config() { return test::gs_config(); }

struct Station {
  Station() : core(config(), ParamTable()) {}
  std::vector<mavlink_message_t> send(const mavlink_message_t& m) {
    uint8_t buf[MAVLINK_MAX_PACKET_LEN];
    const uint16_t n = mavlink_msg_to_send_buffer(buf, &m);
    core.handle_bytes(buf, n, Clock{1000, 1795000000000000ULL});
    return test::decode_all(core.take_frames());
  }
  std::vector<mavlink_message_t> set_home_long(float here, float lat, float lon, float alt) {
    mavlink_message_t m;
    mavlink_msg_command_long_pack(255, 190, &m, 1, 1, MAV_CMD_DO_SET_HOME, 0, here, 0, 0, 0, lat,
                                  lon, alt);
    return send(m);
  }
  std::vector<mavlink_message_t> set_home_int(int32_t x, int32_t y, float alt) {
    mavlink_message_t m;
    mavlink_msg_command_int_pack(255, 190, &m, 1, 1, MAV_FRAME_GLOBAL, MAV_CMD_DO_SET_HOME, 0, 0, 0,
                                 0, 0, 0, x, y, alt);
    return send(m);
  }
  void ha_says_agl_ft(double agl_ft) {
    DecisionInfo d;
    d.altitude_agl_ft = agl_ft;
    core.set_decision(d);
    core.take_frames();
  }
  GsCore core;
};

uint8_t ack_result(const std::vector<mavlink_message_t>& msgs) {
  const auto acks = test::of_type(msgs, MAVLINK_MSG_ID_COMMAND_ACK);
  EXPECT_EQ(acks.size(), 1u);
  return acks.empty() ? 255 : mavlink_msg_command_ack_get_result(&acks[0]);
}

}  // namespace

TEST(GsHome, TelemetryNeverBecomesHomeOnlyTheHasHomeDoes) {
  Station s;
  Telemetry t;
  t.lat_deg = 41.0;
  t.lon_deg = -87.0;
  t.alt_m = 300.0;
  s.core.set_telemetry(t, Clock{1000, 1795000000000000ULL});
  EXPECT_FALSE(s.core.home_known());
  ASSERT_TRUE(s.core.set_home(kHaHome));
  const auto out = test::decode_all(s.core.take_frames());
  const auto homes = test::of_type(out, MAVLINK_MSG_ID_HOME_POSITION);
  ASSERT_EQ(homes.size(), 1u);  // told at once, without being asked
  EXPECT_EQ(mavlink_msg_home_position_get_latitude(&homes[0]), 404237054);
  EXPECT_EQ(mavlink_msg_home_position_get_longitude(&homes[0]), -869211946);
  EXPECT_EQ(mavlink_msg_home_position_get_altitude(&homes[0]), 185250);
  // The same home again (the HA repeats it every few seconds) is no news.
  ASSERT_TRUE(s.core.set_home(kHaHome));
  EXPECT_TRUE(
      test::of_type(test::decode_all(s.core.take_frames()), MAVLINK_MSG_ID_HOME_POSITION).empty());
  // A corrupt one is dropped and the old home kept.
  EXPECT_FALSE(s.core.set_home(GeoPoint{95.0, 0.5, 0.0}));
  EXPECT_EQ(s.core.home().lat_deg, kHaHome.lat_deg);
}

TEST(GsHome, SetHomeOnTheGroundIsForwardedToTheHaWithItsExactPosition) {
  Station s;
  s.ha_says_agl_ft(0.0);
  EXPECT_EQ(ack_result(s.set_home_int(404240000, -869215000, 190.5f)), MAV_RESULT_ACCEPTED);
  auto reqs = s.core.take_home_requests();
  ASSERT_EQ(reqs.size(), 1u);
  EXPECT_FALSE(reqs[0].use_current);
  EXPECT_DOUBLE_EQ(reqs[0].position.lat_deg, 40.424);  // COMMAND_INT: not rounded through a float
  EXPECT_DOUBLE_EQ(reqs[0].position.lon_deg, -86.9215);
  EXPECT_DOUBLE_EQ(reqs[0].position.alt_m, 190.5);
  EXPECT_EQ(ack_result(s.set_home_long(1.0f, 0, 0, 0)), MAV_RESULT_ACCEPTED);  // "here"
  reqs = s.core.take_home_requests();
  ASSERT_EQ(reqs.size(), 1u);
  EXPECT_TRUE(reqs[0].use_current);
}

TEST(GsHome, SetHomeInFlightIsRefusedWithTheReason) {
  Station s;
  s.ha_says_agl_ft(150.0);
  const auto out = s.set_home_long(1.0f, 0, 0, 0);
  EXPECT_EQ(ack_result(out), MAV_RESULT_TEMPORARILY_REJECTED);
  EXPECT_EQ(test::statustexts(out), "Set home refused: in flight");
  EXPECT_TRUE(s.core.take_home_requests().empty());
}

TEST(GsHome, SetHomeWithoutHaStatusOrToANonsensePositionIsRefused) {
  Station s;
  auto out = s.set_home_long(1.0f, 0, 0, 0);
  EXPECT_EQ(ack_result(out), MAV_RESULT_TEMPORARILY_REJECTED);
  EXPECT_NE(test::statustexts(out).find("no HA status"), std::string::npos);
  s.ha_says_agl_ft(0.0);
  out = s.set_home_long(0.0f, 91.0f, 7.0f, 100.0f);
  EXPECT_EQ(ack_result(out), MAV_RESULT_DENIED);
  EXPECT_EQ(test::statustexts(out), "Set home refused: not a valid position");
  EXPECT_TRUE(s.core.take_home_requests().empty());
}

// The ground station keeps a /home, and forwards a SET_HOME to the HA, exactly when the HA's own
// judge (geo_ref_init) would take it: one judge, so it never refuses a home the HA flies about,
// nor passes on one the HA would refuse.
TEST(GsHome, KeepsAndForwardsAHomeExactlyWhenTheHasJudgeDoes) {
  for (const HomeVector& v : kHomeVectors) {
    Station s;
    EXPECT_EQ(s.core.set_home(GeoPoint{v.lat_deg, v.lon_deg, v.alt_m}), v.valid) << v.what;
    EXPECT_EQ(s.core.home_known(), v.valid) << v.what;
    s.ha_says_agl_ft(0.0);  // parked: a SET_HOME is judged on its position alone
    // As QGroundControl sends it: COMMAND_LONG's float parameters.
    EXPECT_EQ(
        ack_result(s.set_home_long(0.0f, static_cast<float>(v.lat_deg),
                                   static_cast<float>(v.lon_deg), static_cast<float>(v.alt_m))),
        v.valid ? MAV_RESULT_ACCEPTED : MAV_RESULT_DENIED)
        << v.what;
    EXPECT_EQ(s.core.take_home_requests().size(), v.valid ? 1u : 0u) << v.what;
  }
}
