// GsCore driven like the node drives it, but with a simulated clock and a MAVLink "ground
// station" built from the same generated library: telemetry schedule, mission state machine
// (timeouts, retries, lost ACK), parameters, commands, signing, corrupt input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>
#include <vector>

#include "gs_core.h"
#include "gs_test_config.h"
#include "gs_test_frames.h"

using namespace microhard_gs;

namespace {

using test::decode_all;
using test::of_type;
using test::statustexts;

constexpr uint64_t kUnixStartUs = 1795000000ULL * 1000000ULL;  // any time after 2015
const GeoPoint kHome{40.11, -88.22, 220.0};

GsConfig base_config() {
  GsConfig c = test::gs_config();
  c.mission.item_timeout_ms = 1500;
  c.mission.max_retries = 5;
  return c;
}

ParamTable some_params() {
  ParamTable t;
  const auto& specs = controller_param_specs();
  for (size_t i = 0; i < specs.size(); ++i) t.add(specs[i], static_cast<double>(i));
  return t;
}

// The ground station side: encodes requests, decodes what the vehicle sent.
class Gcs {
 public:
  explicit Gcs(const SigningKey* key = nullptr) {
    if (key != nullptr) {
      std::memcpy(signing_.secret_key, key->data(), 32);
      signing_.flags = MAVLINK_SIGNING_FLAG_SIGN_OUTGOING;
      signing_.timestamp = (kUnixStartUs - 1420070400ULL * 1000000ULL) / 10;
      tx_.signing = &signing_;
      tx_.signing_streams = &streams_;
    }
  }
  template <typename Encode>
  std::vector<uint8_t> frame(Encode encode) {
    mavlink_message_t msg;
    encode(&msg);
    uint8_t buf[MAVLINK_MAX_PACKET_LEN];
    const uint16_t n = mavlink_msg_to_send_buffer(buf, &msg);
    return std::vector<uint8_t>(buf, buf + n);
  }
  std::vector<uint8_t> command(uint16_t cmd, float p1 = 0, float p2 = 0) {
    return frame([&](mavlink_message_t* m) {
      mavlink_msg_command_long_pack_status(255, 190, &tx_, m, 1, 1, cmd, 0, p1, p2, 0, 0, 0, 0, 0);
    });
  }
  std::vector<uint8_t> count(uint16_t n) {
    return frame([&](mavlink_message_t* m) {
      mavlink_msg_mission_count_pack_status(255, 190, &tx_, m, 1, 1, n, MAV_MISSION_TYPE_MISSION);
    });
  }
  // A waypoint as a GCS sends it in any frame: MISSION_ITEM_INT (lat/lon deg * 1e7) or the
  // legacy MISSION_ITEM (degrees).
  std::vector<uint8_t> waypoint_in(uint16_t seq, uint8_t mav_frame, double lat_deg, double lon_deg,
                                   float z_m, bool legacy = false) {
    return frame([&](mavlink_message_t* m) {
      if (legacy) {
        mavlink_msg_mission_item_pack_status(
            255, 190, &tx_, m, 1, 1, seq, mav_frame, MAV_CMD_NAV_WAYPOINT, 0, 1, 0, 0, 0, 0,
            static_cast<float>(lat_deg), static_cast<float>(lon_deg), z_m,
            MAV_MISSION_TYPE_MISSION);
      } else {
        mavlink_msg_mission_item_int_pack_status(
            255, 190, &tx_, m, 1, 1, seq, mav_frame, MAV_CMD_NAV_WAYPOINT, 0, 1, 0, 0, 0, 0,
            static_cast<int32_t>(std::lround(lat_deg * 1e7)),
            static_cast<int32_t>(std::lround(lon_deg * 1e7)), z_m, MAV_MISSION_TYPE_MISSION);
      }
    });
  }
  std::vector<uint8_t> request_item(uint16_t seq, bool legacy) {
    return frame([&](mavlink_message_t* m) {
      if (legacy) {
        mavlink_msg_mission_request_pack_status(255, 190, &tx_, m, 1, 1, seq,
                                                MAV_MISSION_TYPE_MISSION);
      } else {
        mavlink_msg_mission_request_int_pack_status(255, 190, &tx_, m, 1, 1, seq,
                                                    MAV_MISSION_TYPE_MISSION);
      }
    });
  }
  std::vector<uint8_t> item(uint16_t seq, double north_ft, double east_ft, double height_ft) {
    double lat = 0, lon = 0;
    north_east_ft_to_geodetic(kHome, NorthEastFt{north_ft, east_ft}, &lat, &lon);
    return frame([&](mavlink_message_t* m) {
      mavlink_msg_mission_item_int_pack_status(
          255, 190, &tx_, m, 1, 1, seq, MAV_FRAME_GLOBAL_RELATIVE_ALT_INT, MAV_CMD_NAV_WAYPOINT, 0,
          1, 0, 0, 0, 0, static_cast<int32_t>(std::lround(lat * 1e7)),
          static_cast<int32_t>(std::lround(lon * 1e7)), static_cast<float>(height_ft * 0.3048),
          MAV_MISSION_TYPE_MISSION);
    });
  }

 private:
  mavlink_status_t tx_{};
  mavlink_signing_t signing_{};
  mavlink_signing_streams_t streams_{};
};

class Bench {
 public:
  // with_home: the HA's /home has come (the one home of the stack), its news already taken.
  explicit Bench(const GsConfig& config = base_config(), bool with_home = true)
      : core(config, some_params()) {
    if (with_home) {
      EXPECT_TRUE(core.set_home(kHome));
      (void)core.take_frames();
    }
  }
  Clock at(uint64_t ms) const { return Clock{ms, kUnixStartUs + ms * 1000}; }
  std::vector<mavlink_message_t> feed(const std::vector<uint8_t>& bytes) {
    core.handle_bytes(bytes.data(), bytes.size(), at(now_ms));
    return decode_all(core.take_frames());
  }
  // Advances the simulated clock in 5 ms steps, as the node's poll loop does.
  std::vector<mavlink_message_t> run_for(uint64_t ms) {
    const uint64_t end = now_ms + ms;
    std::vector<std::vector<uint8_t>> frames;
    for (; now_ms < end; now_ms += 5) {
      core.tick(at(now_ms));
      for (auto& f : core.take_frames()) frames.push_back(std::move(f));
    }
    return decode_all(frames);
  }
  GsCore core;
  uint64_t now_ms = 1000;
};

Telemetry flying() {
  Telemetry t;
  t.lat_deg = kHome.lat_deg;
  t.lon_deg = kHome.lon_deg;
  t.alt_m = kHome.alt_m + 60.0;
  t.v_north_mps = 15.0;
  t.airspeed_ftps = 55.0;
  t.ins_link_up = true;
  t.ha_link_up = true;
  t.computer_in_command = true;
  return t;
}

uint8_t ack_of(const mavlink_message_t& m) { return mavlink_msg_mission_ack_get_type(&m); }

}  // namespace

TEST(Telemetry, TenHertzScheduleHoldsOverTenSimulatedSeconds) {
  Bench b;
  b.core.set_telemetry(flying(), b.at(b.now_ms));
  std::vector<mavlink_message_t> msgs;
  for (int s = 0; s < 10; ++s) {  // keep /data fresh, as the controller does
    auto part = b.run_for(1000);
    msgs.insert(msgs.end(), part.begin(), part.end());
    b.core.set_telemetry(flying(), b.at(b.now_ms));
  }
  EXPECT_NEAR(static_cast<double>(of_type(msgs, MAVLINK_MSG_ID_ATTITUDE).size()), 100.0, 1.0);
  EXPECT_NEAR(static_cast<double>(of_type(msgs, MAVLINK_MSG_ID_GLOBAL_POSITION_INT).size()), 100.0,
              1.0);
  EXPECT_NEAR(static_cast<double>(of_type(msgs, MAVLINK_MSG_ID_HEARTBEAT).size()), 10.0, 1.0);
  const auto hb = of_type(msgs, MAVLINK_MSG_ID_HEARTBEAT).front();
  EXPECT_EQ(mavlink_msg_heartbeat_get_type(&hb), MAV_TYPE_FIXED_WING);
  EXPECT_EQ(hb.compid, MAV_COMP_ID_AUTOPILOT1);
  const auto hud = of_type(msgs, MAVLINK_MSG_ID_VFR_HUD).back();
  EXPECT_NEAR(mavlink_msg_vfr_hud_get_airspeed(&hud), 55.0 * 0.3048, 1e-4);
  const auto pos = of_type(msgs, MAVLINK_MSG_ID_GLOBAL_POSITION_INT).back();
  EXPECT_EQ(mavlink_msg_global_position_int_get_relative_alt(&pos), 60000);
}

TEST(Telemetry, StaleDataStopsPositionReportsButNotHeartbeat) {
  Bench b;
  b.core.set_telemetry(flying(), b.at(b.now_ms));
  b.run_for(2500);  // /data went quiet 2.5 s ago
  const auto msgs = b.run_for(2000);
  EXPECT_TRUE(of_type(msgs, MAVLINK_MSG_ID_GLOBAL_POSITION_INT).empty());
  EXPECT_FALSE(of_type(msgs, MAVLINK_MSG_ID_HEARTBEAT).empty());
  EXPECT_FALSE(of_type(msgs, MAVLINK_MSG_ID_SYS_STATUS).empty());
}

TEST(MissionUpload, LostItemsAreRequestedAgainBothWaysAfterTheTimeoutThenTheUploadGivesUp) {
  Bench b;
  b.run_for(10);
  auto out = b.feed(Gcs().count(3));
  ASSERT_EQ(of_type(out, MAVLINK_MSG_ID_MISSION_REQUEST_INT).size(), 1u);
  // The GCS never answers: 5 retries at 1.5 s, asking with MISSION_REQUEST and MISSION_REQUEST_INT
  // in turn, then a cancel ACK and a STATUSTEXT.
  auto msgs = b.run_for(1490);
  EXPECT_TRUE(of_type(msgs, MAVLINK_MSG_ID_MISSION_REQUEST_INT).empty());
  msgs = b.run_for(1500 * 5 + 100);
  EXPECT_EQ(of_type(msgs, MAVLINK_MSG_ID_MISSION_REQUEST).size(), 3u);
  EXPECT_EQ(of_type(msgs, MAVLINK_MSG_ID_MISSION_REQUEST_INT).size(), 2u);
  const auto acks = of_type(msgs, MAVLINK_MSG_ID_MISSION_ACK);
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(ack_of(acks[0]), MAV_MISSION_OPERATION_CANCELLED);
  EXPECT_FALSE(b.core.upload_in_progress());
  EXPECT_EQ(b.core.counters().mission_uploads_timed_out, 1u);
}

TEST(MissionUpload, ThreeItemsAcceptedAndPlanPublished) {
  Bench b;
  Gcs gcs;
  b.feed(gcs.count(3));
  b.feed(gcs.item(0, 0, 0, 150));
  b.feed(gcs.item(1, 500, 0, 200));
  const auto out = b.feed(gcs.item(2, 500, 500, 250));
  const auto acks = of_type(out, MAVLINK_MSG_ID_MISSION_ACK);
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(ack_of(acks[0]), MAV_MISSION_ACCEPTED);
  const auto plans = b.core.take_way_plans();
  ASSERT_EQ(plans.size(), 1u);
  EXPECT_EQ(plans[0].fp, 3);
  EXPECT_NEAR(plans[0].east_ft[2], 500.0, 0.5);
  EXPECT_NEAR(plans[0].height_ft[2], 250.0, 0.01);
}

TEST(MissionUpload, RepeatedLastItemAfterALostAckGetsTheAckAgain) {
  Bench b;
  Gcs gcs;
  b.feed(gcs.count(1));
  auto first = b.feed(gcs.item(0, 0, 0, 150));
  ASSERT_EQ(of_type(first, MAVLINK_MSG_ID_MISSION_ACK).size(), 1u);
  b.run_for(1500);
  const auto again = b.feed(gcs.item(0, 0, 0, 150));
  const auto acks = of_type(again, MAVLINK_MSG_ID_MISSION_ACK);
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(ack_of(acks[0]), MAV_MISSION_ACCEPTED);
  EXPECT_EQ(b.core.take_way_plans().size(), 1u);  // accepted once, not twice
}

TEST(MissionUpload, DuplicateItemIsAnsweredWithARequestForTheNextOne) {
  Bench b;
  Gcs gcs;
  b.feed(gcs.count(3));
  b.feed(gcs.item(0, 0, 0, 150));
  const auto out = b.feed(gcs.item(0, 0, 0, 150));
  const auto reqs = of_type(out, MAVLINK_MSG_ID_MISSION_REQUEST_INT);
  ASSERT_EQ(reqs.size(), 1u);
  EXPECT_EQ(mavlink_msg_mission_request_int_get_seq(&reqs[0]), 1);
}

TEST(MissionUpload, CeilingViolationRejectsAndKeepsTheOldMission) {
  Bench b;
  Gcs gcs;
  b.feed(gcs.count(1));
  b.feed(gcs.item(0, 0, 0, 150));
  b.core.take_way_plans();
  b.feed(gcs.count(2));
  b.feed(gcs.item(0, 0, 0, 150));
  const auto out = b.feed(gcs.item(1, 0, 0, 600));
  const auto acks = of_type(out, MAVLINK_MSG_ID_MISSION_ACK);
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(ack_of(acks[0]), MAV_MISSION_INVALID_PARAM7);
  const auto texts = of_type(out, MAVLINK_MSG_ID_STATUSTEXT);
  ASSERT_FALSE(texts.empty());
  char text[51] = {};
  mavlink_msg_statustext_get_text(&texts[0], text);
  EXPECT_NE(std::string(text).find("ceiling"), std::string::npos) << text;
  EXPECT_TRUE(b.core.take_way_plans().empty());
  EXPECT_EQ(b.core.mission_count(), 1);
}

TEST(MissionUpload, NoHomeMeansDenied) {
  Bench b(base_config(), false);
  Gcs gcs;
  b.feed(gcs.count(1));
  const auto acks = of_type(b.feed(gcs.item(0, 0, 0, 150)), MAVLINK_MSG_ID_MISSION_ACK);
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(ack_of(acks[0]), MAV_MISSION_DENIED);
}

std::vector<uint8_t> param_set(const char* name, float value,
                               uint8_t type = MAV_PARAM_TYPE_REAL32) {
  return Gcs().frame([&](mavlink_message_t* m) {
    char id[16] = {};  // the packer copies all 16 bytes; ids of 16 have no terminator
    std::memcpy(id, name, std::min(sizeof id, std::strlen(name)));
    mavlink_msg_param_set_pack(255, 190, m, 1, 1, id, value, type);
  });
}

float echoed_value(const std::vector<mavlink_message_t>& out, const char* name) {
  const auto values = of_type(out, MAVLINK_MSG_ID_PARAM_VALUE);
  EXPECT_EQ(values.size(), 1u);
  if (values.empty()) return NAN;
  char id[17] = {};
  mavlink_msg_param_value_get_param_id(&values[0], id);
  EXPECT_STREQ(id, name);
  return mavlink_msg_param_value_get_param_value(&values[0]);
}

// some_params() gives each parameter its index in the table as value.
const double kMpfRadiusAtStart = static_cast<double>(some_params().find("mpf_radius", 10));

TEST(Parameters, SetIsAskedOfTheControllerAndEchoedWithTheValueItPutInForce) {
  Bench b;
  EXPECT_TRUE(of_type(b.feed(param_set("mpf_radius", 321.0f)), MAVLINK_MSG_ID_PARAM_VALUE).empty())
      << "no echo before the controller has answered";
  const auto requests = b.core.take_param_set_requests();
  ASSERT_EQ(requests.size(), 1u);
  EXPECT_EQ(requests[0].ros_name, "mpf_radius");
  EXPECT_DOUBLE_EQ(requests[0].value, 321.0);
  b.core.param_set_answered(requests[0], ParamSetAnswer{true, 321.0, ""});
  const auto out = decode_all(b.core.take_frames());
  EXPECT_FLOAT_EQ(echoed_value(out, "mpf_radius"), 321.0f);
  EXPECT_TRUE(of_type(out, MAVLINK_MSG_ID_STATUSTEXT).empty());
  EXPECT_DOUBLE_EQ(b.core.params().at(b.core.params().find("mpf_radius", 10)).value, 321.0);
  EXPECT_EQ(b.core.counters().param_sets_accepted, 1u);
}

TEST(Parameters, RefusedSetIsEchoedWithTheOldValueAndTheReasonAsStatustext) {
  Bench b;
  b.feed(param_set("mpf_radius", -5.0f));
  const auto requests = b.core.take_param_set_requests();
  ASSERT_EQ(requests.size(), 1u);
  b.core.param_set_answered(requests[0],
                            ParamSetAnswer{false, 0.0, "mpf_radius = -5 is outside [20, 5000]"});
  const auto out = decode_all(b.core.take_frames());
  EXPECT_FLOAT_EQ(echoed_value(out, "mpf_radius"), kMpfRadiusAtStart);
  EXPECT_EQ(statustexts(out), "Param mpf_radius refused: mpf_radius = -5 is outside [20, 5000]");
  EXPECT_EQ(mavlink_msg_statustext_get_severity(&of_type(out, MAVLINK_MSG_ID_STATUSTEXT)[0]),
            MAV_SEVERITY_WARNING);
  EXPECT_EQ(b.core.counters().param_sets_refused, 1u);
}

TEST(Parameters, SilentControllerMeansRefusedAfterTheTimeoutAndALateAcceptanceIsStillAnnounced) {
  Bench b;
  b.feed(param_set("KpLon", 0.125f));
  const auto requests = b.core.take_param_set_requests();
  ASSERT_EQ(requests.size(), 1u);
  EXPECT_TRUE(of_type(b.run_for(400), MAVLINK_MSG_ID_PARAM_VALUE).empty());
  const auto out = b.run_for(200);  // past the 500 ms default
  const double old_value = b.core.params().at(b.core.params().find("KpLon", 5)).value;
  EXPECT_FLOAT_EQ(echoed_value(out, "KpLon"), static_cast<float>(old_value));
  EXPECT_NE(statustexts(out).find("no answer from the controller"), std::string::npos)
      << statustexts(out);
  EXPECT_EQ(b.core.counters().param_sets_timed_out, 1u);

  // The controller did take it after all: the GCS must learn the value it now flies with.
  b.core.param_set_answered(requests[0], ParamSetAnswer{true, 0.125, ""});
  const auto late = decode_all(b.core.take_frames());
  EXPECT_FLOAT_EQ(echoed_value(late, "KpLon"), 0.125f);
  EXPECT_NE(statustexts(late).find("late"), std::string::npos);
}

TEST(Parameters, IntegerSetTravelsByteWiseAndAFloatTypedOneGoesToTheControllerAsItIs) {
  Bench b;
  const int32_t two = 1;
  float f;
  std::memcpy(&f, &two, sizeof f);
  b.feed(param_set("path_select", f, MAV_PARAM_TYPE_INT32));
  b.feed(param_set("path_select", 2.5f));
  const auto requests = b.core.take_param_set_requests();
  ASSERT_EQ(requests.size(), 2u);
  EXPECT_DOUBLE_EQ(requests[0].value, 1.0);
  EXPECT_DOUBLE_EQ(requests[1].value, 2.5);  // the controller refuses it: not whole
}

TEST(Parameters, FloodOfSetsIsRefusedOnceSixteenWaitForTheController) {
  Bench b;
  for (int i = 0; i < 16; ++i) b.feed(param_set("dist2b", static_cast<float>(100 + i)));
  EXPECT_EQ(b.core.take_param_set_requests().size(), 16u);
  const auto out = b.feed(param_set("dist2b", 200.0f));
  EXPECT_TRUE(b.core.take_param_set_requests().empty());
  EXPECT_EQ(of_type(out, MAVLINK_MSG_ID_PARAM_VALUE).size(), 1u);
  EXPECT_NE(statustexts(out).find("busy"), std::string::npos);
}

TEST(Parameters, UnknownNameIsIgnoredAsTheProtocolHasNoNegativeAnswer) {
  Bench b;
  EXPECT_TRUE(b.feed(param_set("NO_SUCH_PARAM", 1.0f)).empty());
  EXPECT_TRUE(b.core.take_param_set_requests().empty());
}

TEST(Parameters, ListSendsEveryParameterWithItsIndex) {
  Bench b;
  const auto out = b.feed(Gcs().frame(
      [&](mavlink_message_t* m) { mavlink_msg_param_request_list_pack(255, 190, m, 1, 1); }));
  const auto values = of_type(out, MAVLINK_MSG_ID_PARAM_VALUE);
  ASSERT_EQ(values.size(), controller_param_specs().size());
  EXPECT_EQ(mavlink_msg_param_value_get_param_index(&values.back()), values.size() - 1);
}

TEST(Commands, SelectHaIsForwardedAndAcknowledged) {
  Bench b;
  const auto out = b.feed(Gcs().command(MAV_CMD_DO_SET_MODE, MAV_MODE_FLAG_CUSTOM_MODE_ENABLED, 1));
  const auto acks = of_type(out, MAVLINK_MSG_ID_COMMAND_ACK);
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(mavlink_msg_command_ack_get_result(&acks[0]), MAV_RESULT_ACCEPTED);
  const auto reqs = b.core.take_operator_requests();
  ASSERT_EQ(reqs.size(), 1u);
  EXPECT_EQ(reqs[0], OperatorRequest::kSelectHa);
}

TEST(Commands, UnknownCommandIsUnsupported) {
  Bench b;
  const auto acks = of_type(b.feed(Gcs().command(MAV_CMD_NAV_LAND)), MAVLINK_MSG_ID_COMMAND_ACK);
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(mavlink_msg_command_ack_get_result(&acks[0]), MAV_RESULT_UNSUPPORTED);
  EXPECT_TRUE(b.core.take_operator_requests().empty());
}

// The text a decision status produced (its chunks joined), and its severity.
std::pair<std::string, uint8_t> announced(Bench& b, uint8_t controller,
                                          uint32_t reasons_at_switch = 0) {
  DecisionInfo d;
  d.controller = controller;
  d.reasons_at_switch = reasons_at_switch;
  d.reasons = reasons_at_switch;
  b.core.set_decision(d);
  const auto out = decode_all(b.core.take_frames());
  const auto texts = of_type(out, MAVLINK_MSG_ID_STATUSTEXT);
  EXPECT_FALSE(texts.empty());
  if (texts.empty()) return {"", 0};
  return {statustexts(out), mavlink_msg_statustext_get_severity(&texts[0])};
}

TEST(Decision, SwitchToHaIsAnnouncedWithItsReasons) {
  Bench b;
  announced(b, 0);
  const auto t = announced(b, 1, 2 | 128);  // DEADLINE_MISS, CEILING
  EXPECT_EQ(t.first, "Controller HP->HA: DEADLINE_MISS,CEILING");
  EXPECT_EQ(t.second, MAV_SEVERITY_WARNING);
}

TEST(Decision, FirstStatusSeenIsAnnouncedWithWhoFliesAndWhy) {
  Bench b;
  const auto t = announced(b, 1, 1);  // booting already on the HA: the HP sent nothing yet
  EXPECT_EQ(t.first, "Controller HA (first report): NO_COMMAND");
  EXPECT_EQ(t.second, MAV_SEVERITY_WARNING);
  DecisionInfo same;
  same.controller = 1;
  same.reasons = 1;
  b.core.set_decision(same);
  EXPECT_TRUE(b.core.take_frames().empty());  // no change, no text
}

TEST(Decision, FirstStatusOnTheHpIsAnnouncedToo) {
  Bench b;
  EXPECT_EQ(announced(b, 0).first, "Controller HP (first report): HP command stable");
}

TEST(Decision, EveryStepOfARecoveryNamesItsReason) {
  Bench b;
  announced(b, 0);
  EXPECT_EQ(announced(b, 1, 2048).first, "Controller HP->HA: ESTIMATOR");
  const auto recovering = announced(b, 2);
  EXPECT_EQ(recovering.first,
            "Controller HA->RECOVERING: HP command valid, watching its stability");
  EXPECT_EQ(recovering.second, MAV_SEVERITY_NOTICE);
  EXPECT_EQ(announced(b, 1, 1).first, "Controller RECOVERING->HA: NO_COMMAND");
  EXPECT_EQ(announced(b, 2).first,
            "Controller HA->RECOVERING: HP command valid, watching its stability");
  EXPECT_EQ(announced(b, 0).first, "Controller RECOVERING->HP: HP command stable");
}

TEST(Decision, LatchingNamesTheRestartCapAndTheReasons) {
  Bench b;
  announced(b, 1, 1);
  const auto t = announced(b, 3, 1);
  EXPECT_EQ(t.first, "Controller HA->HA_LATCHED: restart cap reached; NO_COMMAND");
  EXPECT_EQ(t.second, MAV_SEVERITY_CRITICAL);
}

TEST(Decision, PilotTakingAndHandingBackCommandIsAnnouncedAsThePicSwitch) {
  Bench b;
  announced(b, 0);
  EXPECT_EQ(announced(b, 4).first, "Controller HP->MANUAL: pilot in command (PIC switch)");
  EXPECT_EQ(announced(b, 1, 4096).first,
            "Controller MANUAL->HA: PIC switch to computer; GROUND_COMMAND");
  announced(b, 4);
  EXPECT_EQ(announced(b, 1).first,
            "Controller MANUAL->HA: PIC switch to computer; no reason reported");
}

TEST(Decision, UnknownControllerValueIsStillAnnounced) {
  Bench b;
  announced(b, 0);
  const auto t = announced(b, 9, 64);
  EXPECT_EQ(t.first, "Controller HP->UNKNOWN: STALL");
}

TEST(Decision, LongReasonListIsSentInChunks) {
  Bench b;
  DecisionInfo d;
  b.core.set_decision(d);
  b.core.take_frames();  // the first report
  d.controller = 3;
  d.reasons_at_switch = 0x1FFF;  // every reason
  b.core.set_decision(d);
  const auto texts = of_type(decode_all(b.core.take_frames()), MAVLINK_MSG_ID_STATUSTEXT);
  ASSERT_GE(texts.size(), 3u);
  std::string joined;
  for (const auto& t : texts) {
    EXPECT_NE(mavlink_msg_statustext_get_id(&t), 0);
    char text[51] = {};
    mavlink_msg_statustext_get_text(&t, text);
    joined += text;
  }
  EXPECT_NE(joined.find("GROUND_COMMAND"), std::string::npos) << joined;
  EXPECT_EQ(mavlink_msg_statustext_get_severity(&texts[0]), MAV_SEVERITY_CRITICAL);
}

// The key the tests sign with (bytes 1..32), and a ground station that demands it.
SigningKey test_signing_key() {
  SigningKey key{};
  for (size_t i = 0; i < key.size(); ++i) key[i] = static_cast<uint8_t>(i + 1);
  return key;
}

GsConfig signing_config(const SigningKey& key) {
  GsConfig c = base_config();
  c.signing = true;
  c.signing_key = key;
  return c;
}

TEST(Signing, UnsignedCommandIsRefusedWithDeniedAndCounted) {
  const SigningKey key = test_signing_key();
  GsConfig c = signing_config(key);
  Bench b(c);
  b.run_for(10);
  Gcs signed_gcs(&key);
  auto out = b.feed(signed_gcs.command(MAV_CMD_DO_SET_MODE, MAV_MODE_FLAG_CUSTOM_MODE_ENABLED, 1));
  auto acks = of_type(out, MAVLINK_MSG_ID_COMMAND_ACK);
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(mavlink_msg_command_ack_get_result(&acks[0]), MAV_RESULT_ACCEPTED);
  EXPECT_EQ(b.core.take_operator_requests().size(), 1u);

  b.run_for(100);
  out = b.feed(Gcs().command(MAV_CMD_DO_SET_MODE, MAV_MODE_FLAG_CUSTOM_MODE_ENABLED, 1));
  acks = of_type(out, MAVLINK_MSG_ID_COMMAND_ACK);
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(mavlink_msg_command_ack_get_result(&acks[0]), MAV_RESULT_DENIED);
  EXPECT_TRUE(b.core.take_operator_requests().empty());
  EXPECT_EQ(b.core.counters().refused_unsigned, 1u);

  SigningKey wrong = key;
  wrong[0] ^= 0xFF;
  b.feed(Gcs(&wrong).count(2));
  EXPECT_FALSE(b.core.upload_in_progress());
  EXPECT_EQ(b.core.counters().refused_bad_signature, 1u);
}

TEST(Robustness, CorruptFramesAreCountedAndTheNextGoodFrameStillParses) {
  Bench b;
  auto bad = Gcs().command(MAV_CMD_DO_SET_MODE, MAV_MODE_FLAG_CUSTOM_MODE_ENABLED, 1);
  bad[bad.size() - 1] ^= 0x55;
  b.feed(bad);
  EXPECT_EQ(b.core.counters().frames_bad_crc, 1u);
  EXPECT_TRUE(b.core.take_operator_requests().empty());
  b.feed(Gcs().command(MAV_CMD_DO_SET_MODE, MAV_MODE_FLAG_CUSTOM_MODE_ENABLED, 0));
  EXPECT_EQ(b.core.take_operator_requests().size(), 1u);
}

// What the telemetry log gets of the received side: each whole frame with a good CRC, byte for
// byte, however the link chunked it; refused ones too (what the link carried), corrupt ones not.
TEST(ReceivedFrames, EveryGoodFrameIsKeptAsItCameCorruptOnesAreNot) {
  const SigningKey key = test_signing_key();
  GsConfig c = signing_config(key);
  c.keep_received_frames = true;
  Bench b(c);
  b.run_for(10);
  const auto signed_count = Gcs(&key).count(2);
  const auto unsigned_command = Gcs().command(MAV_CMD_DO_SET_MODE, 1, 1);  // refused: unsigned
  auto corrupt = Gcs().command(MAV_CMD_DO_SET_MODE, 1, 0);
  corrupt[corrupt.size() - 1] ^= 0x55;
  const std::vector<uint8_t> garbage{0x00, 0xFD, 0x42, 0x13};  // a stray STX among them
  std::vector<uint8_t> stream = garbage;
  for (const std::vector<uint8_t>* f :
       std::vector<const std::vector<uint8_t>*>{&signed_count, &corrupt, &unsigned_command}) {
    stream.insert(stream.end(), f->begin(), f->end());
  }
  for (uint8_t byte : stream) b.feed({byte});  // a serial link: one byte at a time
  const auto kept = b.core.take_received_frames();
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_EQ(kept[0], signed_count);
  EXPECT_EQ(kept[1], unsigned_command);
  EXPECT_EQ(b.core.counters().frames_bad_crc, 1u);
  EXPECT_TRUE(b.core.take_received_frames().empty());  // taken once

  b.feed(stream);  // a datagram holding them all
  const auto again = b.core.take_received_frames();
  ASSERT_EQ(again.size(), 2u);
  EXPECT_EQ(again[0], signed_count);  // a replay now: refused, still what the link carried
  EXPECT_EQ(again[1], unsigned_command);
}

TEST(ReceivedFrames, NoneAreKeptUnlessAsked) {
  Bench b;
  b.feed(Gcs().command(MAV_CMD_DO_SET_MODE, 1, 0));
  EXPECT_EQ(b.core.counters().frames_ok, 1u);
  EXPECT_TRUE(b.core.take_received_frames().empty());
}

TEST(SigningKeyFile, HexKeyParsesAndGarbageIsRefused) {
  SigningKey key{};
  std::string error;
  EXPECT_TRUE(parse_signing_key(std::string(64, 'a') + "\n", &key, &error));
  EXPECT_EQ(key[0], 0xaa);
  EXPECT_FALSE(parse_signing_key(std::string(63, 'a'), &key, &error));
  EXPECT_FALSE(parse_signing_key(std::string(62, 'a') + "zz", &key, &error));
  EXPECT_FALSE(parse_signing_key(std::string(64, '0'), &key, &error));
}

// ---------------------------------------------------------------- frames, item 0, modes, fence

namespace {
double lat_of(double north_ft) {
  double lat = 0, lon = 0;
  north_east_ft_to_geodetic(kHome, NorthEastFt{north_ft, 0.0}, &lat, &lon);
  return lat;
}
}  // namespace

TEST(MissionUpload, GcsThatAnswersOnlyMissionRequestGetsItsUploadThrough) {
  // MAVProxy answers MISSION_REQUEST (with MISSION_ITEM_INT) and ignores MISSION_REQUEST_INT.
  Bench b;
  Gcs gcs;
  ASSERT_EQ(of_type(b.feed(gcs.count(2)), MAVLINK_MSG_ID_MISSION_REQUEST_INT).size(), 1u);
  const auto retry = b.run_for(1600);
  const auto legacy = of_type(retry, MAVLINK_MSG_ID_MISSION_REQUEST);
  ASSERT_EQ(legacy.size(), 1u);
  EXPECT_EQ(mavlink_msg_mission_request_get_seq(&legacy[0]), 0);
  auto out =
      b.feed(gcs.waypoint_in(0, MAV_FRAME_GLOBAL_RELATIVE_ALT, lat_of(0), kHome.lon_deg, 60.0f));
  const auto next = of_type(out, MAVLINK_MSG_ID_MISSION_REQUEST);
  ASSERT_EQ(next.size(), 1u) << "keeps asking the way that was answered";
  EXPECT_EQ(mavlink_msg_mission_request_get_seq(&next[0]), 1);
  out =
      b.feed(gcs.waypoint_in(1, MAV_FRAME_GLOBAL_RELATIVE_ALT, lat_of(500), kHome.lon_deg, 60.0f));
  const auto acks = of_type(out, MAVLINK_MSG_ID_MISSION_ACK);
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(ack_of(acks[0]), MAV_MISSION_ACCEPTED);
}

// A waypoint uploaded in frame (as a MISSION_ITEM if legacy, else a MISSION_ITEM_INT), 200 ft
// above home, is flown at 200 ft and downloads in its frame: frame as a MISSION_ITEM_INT,
// float_frame as a MISSION_ITEM (which carries degrees).
void expect_item_round_trip(uint8_t frame, bool legacy, uint8_t float_frame) {
  Bench b;
  Gcs gcs;
  const bool absolute = frame == MAV_FRAME_GLOBAL || frame == MAV_FRAME_GLOBAL_INT;
  const float z_m = static_cast<float>((absolute ? kHome.alt_m : 0.0) + 200.0 * 0.3048);
  b.feed(gcs.count(1));
  const auto acks =
      of_type(b.feed(gcs.waypoint_in(0, frame, lat_of(300), kHome.lon_deg, z_m, legacy)),
              MAVLINK_MSG_ID_MISSION_ACK);
  ASSERT_EQ(acks.size(), 1u);
  ASSERT_EQ(ack_of(acks[0]), MAV_MISSION_ACCEPTED);
  const auto plans = b.core.take_way_plans();
  ASSERT_EQ(plans.size(), 1u);
  EXPECT_NEAR(plans[0].height_ft[0], 200.0, 0.01);
  EXPECT_NEAR(plans[0].north_ft[0], 300.0, legacy ? 3.0 : 0.5);

  const auto as_int = of_type(b.feed(gcs.request_item(0, false)), MAVLINK_MSG_ID_MISSION_ITEM_INT);
  ASSERT_EQ(as_int.size(), 1u);
  EXPECT_EQ(mavlink_msg_mission_item_int_get_frame(&as_int[0]), frame);
  EXPECT_FLOAT_EQ(mavlink_msg_mission_item_int_get_z(&as_int[0]), z_m);
  EXPECT_NEAR(mavlink_msg_mission_item_int_get_x(&as_int[0]), lat_of(300) * 1e7, legacy ? 40 : 1);
  const auto as_float = of_type(b.feed(gcs.request_item(0, true)), MAVLINK_MSG_ID_MISSION_ITEM);
  ASSERT_EQ(as_float.size(), 1u);
  EXPECT_EQ(mavlink_msg_mission_item_get_frame(&as_float[0]), float_frame);
  EXPECT_NEAR(mavlink_msg_mission_item_get_x(&as_float[0]), lat_of(300), 1e-5);
}

TEST(MissionDownload, EachItemComesBackInTheFrameItWasUploadedIn) {
  // Every global frame, in both item messages, 200 ft above home; downloads answer in the
  // uploaded frame (a MISSION_ITEM, which carries degrees, gives 5 and 6 as 0 and 3).
  struct Case {
    uint8_t frame;
    uint8_t float_frame;
  };
  const Case frames[] = {
      {MAV_FRAME_GLOBAL, MAV_FRAME_GLOBAL},
      {MAV_FRAME_GLOBAL_RELATIVE_ALT, MAV_FRAME_GLOBAL_RELATIVE_ALT},
      {MAV_FRAME_GLOBAL_INT, MAV_FRAME_GLOBAL},
      {MAV_FRAME_GLOBAL_RELATIVE_ALT_INT, MAV_FRAME_GLOBAL_RELATIVE_ALT},
  };
  for (const bool legacy : {false, true}) {
    for (const Case& c : frames) {
      SCOPED_TRACE(testing::Message()
                   << "frame " << int(c.frame) << (legacy ? " MISSION_ITEM" : " MISSION_ITEM_INT"));
      expect_item_round_trip(c.frame, legacy, c.float_frame);
    }
  }
}

TEST(MissionCurrent, CountsMissionItemsNotWaypoints) {
  // Item 0 is home (not flown) and item 2 a speed change: the controller's second waypoint
  // (waypoint_index 1) is mission item 3.
  Bench b;
  Gcs gcs;
  b.feed(gcs.count(4));
  b.feed(gcs.waypoint_in(0, MAV_FRAME_GLOBAL, kHome.lat_deg, kHome.lon_deg,
                         static_cast<float>(kHome.alt_m)));
  b.feed(gcs.item(1, 300, 0, 200));
  b.feed(gcs.frame([&](mavlink_message_t* m) {
    mavlink_msg_mission_item_int_pack(255, 190, m, 1, 1, 2, MAV_FRAME_MISSION,
                                      MAV_CMD_DO_CHANGE_SPEED, 0, 1, 0, 20.0f, -1, 0, 0, 0, 0,
                                      MAV_MISSION_TYPE_MISSION);
  }));
  const auto done = b.feed(gcs.item(3, 600, 0, 200));
  const auto acks = of_type(done, MAVLINK_MSG_ID_MISSION_ACK);
  ASSERT_EQ(acks.size(), 1u);
  ASSERT_EQ(ack_of(acks[0]), MAV_MISSION_ACCEPTED);
  EXPECT_EQ(statustexts(done), "Mission accepted: 2 waypoints, item 0 is home (not flown)");
  Telemetry t = flying();
  t.waypoint_index = 1;
  b.core.set_telemetry(t, b.at(b.now_ms));
  const auto current = of_type(b.run_for(200), MAVLINK_MSG_ID_MISSION_CURRENT);
  ASSERT_FALSE(current.empty());
  EXPECT_EQ(mavlink_msg_mission_current_get_seq(&current.back()), 3);
  EXPECT_EQ(mavlink_msg_mission_current_get_total(&current.back()), 4);
}

std::string mode_name(const mavlink_message_t& m) {
  char name[36] = {};
  mavlink_msg_available_modes_get_mode_name(&m, name);
  return name;
}

TEST(Modes, AvailableModesNameEveryControllerAndOnlyHpAndHaCanBeSelected) {
  Bench b;
  auto out = b.feed(Gcs().command(MAV_CMD_REQUEST_MESSAGE, MAVLINK_MSG_ID_AVAILABLE_MODES, 0));
  const auto acks = of_type(out, MAVLINK_MSG_ID_COMMAND_ACK);
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(mavlink_msg_command_ack_get_result(&acks[0]), MAV_RESULT_ACCEPTED);
  const auto modes = of_type(out, MAVLINK_MSG_ID_AVAILABLE_MODES);
  ASSERT_EQ(modes.size(), 5u);
  const char* names[] = {"HP", "HA", "RECOVERING", "HA_LATCHED", "MANUAL"};
  for (uint32_t i = 0; i < 5; ++i) {
    EXPECT_EQ(mode_name(modes[i]), names[i]);
    EXPECT_EQ(mavlink_msg_available_modes_get_custom_mode(&modes[i]),
              i);  // = DecisionStatus.controller
    EXPECT_EQ(mavlink_msg_available_modes_get_mode_index(&modes[i]), i + 1);
    EXPECT_EQ(mavlink_msg_available_modes_get_number_modes(&modes[i]), 5);
    const bool selectable = (mavlink_msg_available_modes_get_properties(&modes[i]) &
                             MAV_MODE_PROPERTY_NOT_USER_SELECTABLE) == 0;
    EXPECT_EQ(selectable, i <= 1) << names[i];
  }
  // QGroundControl asks for one index at a time.
  out = b.feed(Gcs().command(MAV_CMD_REQUEST_MESSAGE, MAVLINK_MSG_ID_AVAILABLE_MODES, 4));
  ASSERT_EQ(of_type(out, MAVLINK_MSG_ID_AVAILABLE_MODES).size(), 1u);
  EXPECT_EQ(mode_name(of_type(out, MAVLINK_MSG_ID_AVAILABLE_MODES)[0]), "HA_LATCHED");
  out = b.feed(Gcs().command(MAV_CMD_REQUEST_MESSAGE, MAVLINK_MSG_ID_AVAILABLE_MODES, 6));
  EXPECT_EQ(mavlink_msg_command_ack_get_result(&of_type(out, MAVLINK_MSG_ID_COMMAND_ACK)[0]),
            MAV_RESULT_DENIED);
  EXPECT_TRUE(of_type(out, MAVLINK_MSG_ID_AVAILABLE_MODES).empty());
}

TEST(Modes, HeartbeatAndCurrentModeAgreeOnWhoFliesAndAChangeIsSentAtOnce) {
  Bench b;
  b.core.set_telemetry(flying(), b.at(b.now_ms));  // computer_in_command: must not decide the mode
  DecisionInfo d;
  d.controller = kControllerManual;
  d.altitude_agl_ft = 120.0;
  b.core.set_decision(d);
  const auto at_once = of_type(decode_all(b.core.take_frames()), MAVLINK_MSG_ID_CURRENT_MODE);
  ASSERT_EQ(at_once.size(), 1u);
  EXPECT_EQ(mavlink_msg_current_mode_get_custom_mode(&at_once[0]), kControllerManual);
  const auto msgs = b.run_for(1100);
  const auto hbs = of_type(msgs, MAVLINK_MSG_ID_HEARTBEAT);
  ASSERT_FALSE(hbs.empty());
  EXPECT_EQ(mavlink_msg_heartbeat_get_custom_mode(&hbs.back()), kControllerManual);
  const uint8_t base = mavlink_msg_heartbeat_get_base_mode(&hbs.back());
  EXPECT_TRUE(base & MAV_MODE_FLAG_CUSTOM_MODE_ENABLED);
  EXPECT_TRUE(base & MAV_MODE_FLAG_MANUAL_INPUT_ENABLED);
  EXPECT_FALSE(base & MAV_MODE_FLAG_AUTO_ENABLED);
  EXPECT_TRUE(base & MAV_MODE_FLAG_SAFETY_ARMED);
  EXPECT_FALSE(of_type(msgs, MAVLINK_MSG_ID_CURRENT_MODE).empty()) << "streamed with the heartbeat";

  b.feed(Gcs().command(MAV_CMD_DO_SET_MODE, MAV_MODE_FLAG_CUSTOM_MODE_ENABLED, 1));
  d.controller = kControllerHp;
  b.core.set_decision(d);
  const auto now = of_type(decode_all(b.core.take_frames()), MAVLINK_MSG_ID_CURRENT_MODE);
  ASSERT_EQ(now.size(), 1u);
  EXPECT_EQ(mavlink_msg_current_mode_get_custom_mode(&now[0]), kControllerHp);
  EXPECT_EQ(mavlink_msg_current_mode_get_intended_custom_mode(&now[0]), kControllerHa)
      << "the operator asked for the HA";
  const auto hb = of_type(b.run_for(1100), MAVLINK_MSG_ID_HEARTBEAT);
  ASSERT_FALSE(hb.empty());
  EXPECT_TRUE(mavlink_msg_heartbeat_get_base_mode(&hb.back()) & MAV_MODE_FLAG_AUTO_ENABLED);
  EXPECT_FALSE(mavlink_msg_heartbeat_get_base_mode(&hb.back()) &
               MAV_MODE_FLAG_MANUAL_INPUT_ENABLED);
}

TEST(Telemetry, NoGeofenceIsReportedAbsentAndHealthySoNoBreachIsShown) {
  Bench b;
  b.core.set_telemetry(flying(), b.at(b.now_ms));
  const auto status = of_type(b.run_for(200), MAVLINK_MSG_ID_SYS_STATUS);
  ASSERT_FALSE(status.empty());
  EXPECT_EQ(mavlink_msg_sys_status_get_onboard_control_sensors_present(&status[0]) &
                MAV_SYS_STATUS_GEOFENCE,
            0u);
  EXPECT_EQ(mavlink_msg_sys_status_get_onboard_control_sensors_enabled(&status[0]) &
                MAV_SYS_STATUS_GEOFENCE,
            0u);
  EXPECT_EQ(mavlink_msg_sys_status_get_onboard_control_sensors_health(&status[0]) &
                MAV_SYS_STATUS_GEOFENCE,
            static_cast<uint32_t>(MAV_SYS_STATUS_GEOFENCE));
}
