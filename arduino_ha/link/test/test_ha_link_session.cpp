// The Due's link session as the host sees it: topic negotiation answers the documented topic
// request, time sync, commands handed to the core with their arrival time, logs, parameters,
// and a silent or departing host noticed.
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "ha_link.h"
#include "link_test_util.h"

using link_test::Bytes;
using link_test::frame;

namespace {

const Bytes kTopicRequest{0xFF, 0xFE, 0x00, 0x00, 0xFF, 0x00, 0x00, 0xFF};

struct Device {
  HaLink link;
  link_test::Capture tx;
  std::vector<std::pair<HaHpCommand, uint32_t>> commands;
  std::vector<uint8_t> operator_requests;
  drone_ros_OperatorCommand last_operator{};
  std::vector<int32_t> param_ints;

  Device() {
    HaLinkCallbacks cb{};
    cb.write = &link_test::Capture::write;
    cb.on_command = [](void *ctx, const HaHpCommand *cmd, uint32_t at_us) {
      static_cast<Device *>(ctx)->commands.emplace_back(*cmd, at_us);
    };
    cb.on_operator = [](void *ctx, const drone_ros_OperatorCommand *op, uint32_t) {
      static_cast<Device *>(ctx)->operator_requests.push_back(op->command);
      static_cast<Device *>(ctx)->last_operator = *op;
    };
    cb.on_param = [](void *ctx, const rosserial_msgs_RequestParamResponse *r) {
      for (uint32_t i = 0; i < r->ints_count; ++i)
        static_cast<Device *>(ctx)->param_ints.push_back(r->ints[i]);
    };
    cb.ctx = this;
    ha_link_init(&link, &cb);
    // The capture is a member: route writes to it, not to the Device.
    link.cb.ctx = this;
    link.cb.write = [](void *ctx, const uint8_t *d, size_t n) {
      link_test::Capture::write(&static_cast<Device *>(ctx)->tx, d, n);
    };
  }
  void rx(const Bytes &b, uint32_t now_us) { ha_link_receive(&link, b.data(), b.size(), now_us); }
  Bytes time_reply(uint32_t sec, uint32_t nsec) {
    Bytes p;
    link_test::put_u32(p, sec);
    link_test::put_u32(p, nsec);
    return frame(10, p);
  }
};

struct TopicInfoWire {
  uint16_t id;
  std::string name, type, md5;
  int32_t buffer_size;
};

// rosserial_msgs/TopicInfo: uint16 topic_id, string topic_name, string message_type,
// string md5sum, int32 buffer_size.
TopicInfoWire parse_topic_info(const Bytes &p) {
  size_t pos = 0;
  auto u32 = [&]() {
    uint32_t v = static_cast<uint32_t>(p.at(pos)) | static_cast<uint32_t>(p.at(pos + 1)) << 8 |
                 static_cast<uint32_t>(p.at(pos + 2)) << 16 |
                 static_cast<uint32_t>(p.at(pos + 3)) << 24;
    pos += 4;
    return v;
  };
  auto str = [&]() {
    const uint32_t n = u32();
    std::string s(p.begin() + static_cast<long>(pos), p.begin() + static_cast<long>(pos + n));
    pos += n;
    return s;
  };
  TopicInfoWire t;
  t.id = static_cast<uint16_t>(p.at(0) | p.at(1) << 8);
  pos = 2;
  t.name = str();
  t.type = str();
  t.md5 = str();
  t.buffer_size = static_cast<int32_t>(u32());
  EXPECT_EQ(pos, p.size());
  return t;
}

}  // namespace

TEST(HaLinkSession, HostTopicRequestIsAnsweredWithEveryTopicAndThenATimeRequest) {
  Device d;
  d.rx(kTopicRequest, 1000u);
  const auto frames = d.tx.frames();
  ASSERT_EQ(frames.size(), 6u);
  std::vector<TopicInfoWire> infos;
  for (size_t i = 0; i < 5; ++i) infos.push_back(parse_topic_info(frames[i].second));
  EXPECT_EQ(frames[0].first, 0u);  // ID_PUBLISHER
  EXPECT_EQ(infos[0].name, "pwm");
  EXPECT_EQ(infos[0].type, "drone_ros/pwm");
  EXPECT_EQ(infos[0].md5, "0142956581c4f433f915c54487cd0567");
  EXPECT_GE(infos[0].id, 100u);
  EXPECT_EQ(frames[1].first, 0u);
  EXPECT_EQ(infos[1].type, "drone_ros/DecisionStatus");
  EXPECT_EQ(frames[2].first, 0u);
  EXPECT_EQ(infos[2].name, "home");
  EXPECT_EQ(infos[2].type, "drone_ros/HomePosition");
  EXPECT_EQ(infos[2].md5, "79ae516de68762e84f4220889c161ec5");
  EXPECT_EQ(frames[3].first, 1u);  // ID_SUBSCRIBER
  EXPECT_EQ(infos[3].name, "servo_op");
  EXPECT_EQ(infos[3].md5, "aa3c1563aed64772cc32f85160797a04");
  EXPECT_EQ(infos[3].buffer_size, 256);
  EXPECT_EQ(frames[4].first, 1u);
  EXPECT_EQ(infos[4].type, "drone_ros/OperatorCommand");
  EXPECT_EQ(frames[5].first, 10u);  // std_msgs/Time request
  EXPECT_EQ(frames[5].second.size(), 8u);
  EXPECT_TRUE(ha_link_connected(&d.link));
}

TEST(HaLinkSession, TimeReplySetsRosTimeCorrectedByHalfTheRoundTrip) {
  Device d;
  d.rx(kTopicRequest, 1000u);
  d.rx(d.time_reply(1700000000u, 999000000u), 5000u);  // round trip 4 ms
  const HaRosTime now = ha_link_ros_time(&d.link, 5000u);
  EXPECT_EQ(now.sec, 1700000001u);
  EXPECT_EQ(now.nsec, 1000000u);  // 999 ms + 2 ms
  const HaRosTime later = ha_link_ros_time(&d.link, 1005000u);
  EXPECT_EQ(later.sec, 1700000002u);
  EXPECT_EQ(d.link.counters.time_syncs, 1u);
}

namespace {
double seconds(HaRosTime t) { return t.sec + t.nsec * 1e-9; }
}  // namespace

// A loaded host (a lockstep HiL on a busy machine) answers a time request with a clock 60 ms
// behind the one the HA keeps. The HA's stamps stay where they were until its new clock passes
// them, so /decision_status never runs backwards and a log sorted by stamp keeps its order.
TEST(HaLinkSession, LateTimeReplyHoldsTheStampsInsteadOfSettingThemBack) {
  Device d;
  d.rx(kTopicRequest, 0u);
  d.rx(d.time_reply(100u, 0u), 0u);
  const double before = seconds(ha_link_ros_time(&d.link, 1000000u));  // 101.000
  ha_link_poll(&d.link, 1000000u);                 // the next time request, answered at once
  d.rx(d.time_reply(100u, 940000000u), 1000000u);  // with 100.940
  double last = before;
  for (uint32_t t = 1000000u; t <= 1200000u; t += 10000u) {
    const double stamp = seconds(ha_link_ros_time(&d.link, t));
    EXPECT_GE(stamp, last) << t;
    last = stamp;
    if (t <= 1060000u) {
      EXPECT_DOUBLE_EQ(stamp, before) << t;  // held
    } else {
      EXPECT_NEAR(stamp, 100.94 + (t - 1000000u) * 1e-6, 1e-9) << t;  // the host's clock again
    }
  }
}

// A host clock that starts again (a restarted simulation from 0, a host stepped by hours) is a
// new clock, not a late answer: the stamps follow it at once.
TEST(HaLinkSession, TimeReplyFromAClockThatStartedAgainIsFollowedAtOnce) {
  Device d;
  d.rx(kTopicRequest, 0u);
  d.rx(d.time_reply(1700000000u, 0u), 0u);
  ha_link_poll(&d.link, 1000000u);
  d.rx(d.time_reply(5u, 0u), 1000000u);
  EXPECT_DOUBLE_EQ(seconds(ha_link_ros_time(&d.link, 1000000u)), 5.0);
  EXPECT_DOUBLE_EQ(seconds(ha_link_ros_time(&d.link, 1500000u)), 5.5);
}

TEST(HaLinkSession, ServoCommandBuiltFromTheMsgLayoutReachesTheCoreWithItsArrivalTime) {
  Device d;
  link_test::Cmd c;
  c.seq = 4000000123u;
  c.crc = 0xDEADBEEFu;
  d.rx(frame(100, link_test::servo_command_payload(c)), 777u);
  ASSERT_EQ(d.commands.size(), 1u);
  const HaHpCommand &got = d.commands[0].first;
  EXPECT_EQ(got.seq, 4000000123u);
  EXPECT_EQ(got.stamp_sec, c.sec);
  EXPECT_EQ(got.stamp_nsec, c.nsec);
  EXPECT_FLOAT_EQ(got.elevator_deg, -2.0f);
  EXPECT_FLOAT_EQ(got.beta_est_deg, -0.5f);
  EXPECT_EQ(got.estimator_converged, 1u);
  EXPECT_EQ(got.crc32, 0xDEADBEEFu);  // the link leaves the CRC to the core
  EXPECT_EQ(d.commands[0].second, 777u);
}

TEST(HaLinkSession, TruncatedOrPaddedCommandIsCountedNotDelivered) {
  Device d;
  Bytes p = link_test::servo_command_payload(link_test::Cmd{});
  Bytes shorter(p.begin(), p.end() - 1);
  Bytes longer = p;
  longer.push_back(0);
  d.rx(frame(100, shorter), 0u);
  d.rx(frame(100, longer), 0u);
  EXPECT_TRUE(d.commands.empty());
  EXPECT_EQ(d.link.counters.bad_payload, 2u);
}

TEST(HaLinkSession, UnknownTopicIdIsCountedAndTheLinkCarriesOn) {
  Device d;
  d.rx(frame(4242, Bytes{1, 2, 3}), 0u);
  d.rx(frame(100, link_test::servo_command_payload(link_test::Cmd{})), 0u);
  EXPECT_EQ(d.link.counters.unknown_topic, 1u);
  EXPECT_EQ(d.commands.size(), 1u);
}

TEST(HaLinkSession, NothingIsPublishedBeforeTheHostAsksForTopics) {
  Device d;
  drone_ros_pwm pwm{};
  EXPECT_FALSE(ha_link_publish_pwm(&d.link, &pwm));
  EXPECT_TRUE(d.tx.bytes.empty());
  d.rx(kTopicRequest, 0u);
  d.tx.bytes.clear();
  pwm.PICCIC = 1;
  pwm.velocity = 88.5;
  EXPECT_TRUE(ha_link_publish_pwm(&d.link, &pwm));
  const auto frames = d.tx.frames();
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].first, HA_LINK_TOPIC_PWM);
  // Header (seq, stamp, empty frame_id) 16 bytes, PICCIC, 6 float64, usbstatus.
  EXPECT_EQ(frames[0].second.size(), 16u + 1u + 48u + 1u);
  EXPECT_EQ(frames[0].second[16], 1u);
}

// Home costs the link 44 bytes a time: sent at once when latched or moved and to a host that
// (re)negotiates, then every 2 s, never every period.
TEST(HaLinkSession, HomeIsSentWhenItChangesAndEveryTwoSecondsNotEveryPeriod) {
  Device d;
  drone_ros_HomePosition home{};
  d.rx(kTopicRequest, 0u);
  d.tx.bytes.clear();
  auto homes_sent = [&d]() {
    size_t n = 0;
    for (const auto &f : d.tx.frames()) n += f.first == HA_LINK_TOPIC_HOME ? 1u : 0u;
    return n;
  };
  uint32_t t = 0;
  for (; t < 100000u; t += 10000u) ha_link_offer_home(&d.link, &home, t);  // seq 0: no home yet
  EXPECT_EQ(homes_sent(), 0u);
  home.seq = 1;
  home.latitude = 40.4237054;
  for (; t < 1000000u; t += 10000u) ha_link_offer_home(&d.link, &home, t);
  EXPECT_EQ(homes_sent(), 1u);  // 90 periods, one frame
  const auto frames = d.tx.frames();
  EXPECT_EQ(frames.back().second.size(), 36u);
  for (; t < 3100000u; t += 10000u) ha_link_offer_home(&d.link, &home, t);
  EXPECT_EQ(homes_sent(), 2u);  // the repeat, 2 s after the first
  home.seq = 2;                 // moved (an accepted SET_HOME): at once
  ha_link_offer_home(&d.link, &home, t);
  EXPECT_EQ(homes_sent(), 3u);
  d.rx(kTopicRequest, t + 10000u);  // the host came back: it hears home at once
  ha_link_offer_home(&d.link, &home, t + 20000u);
  EXPECT_EQ(homes_sent(), 4u);
}

TEST(HaLinkSession, SilentHostIsNoticedAndPublishingStopsUntilItAsksAgain) {
  Device d;
  d.rx(kTopicRequest, 0u);
  uint32_t t = 0;
  for (; t <= 3000000u; t += 10000u) ha_link_poll(&d.link, t);  // 3 s, no time replies
  EXPECT_FALSE(ha_link_connected(&d.link));
  EXPECT_EQ(d.link.counters.sync_losses, 1u);
  drone_ros_DecisionStatus status{};
  EXPECT_FALSE(ha_link_publish_decision_status(&d.link, &status));
  d.rx(kTopicRequest, t);
  EXPECT_TRUE(ha_link_connected(&d.link));
  EXPECT_TRUE(ha_link_publish_decision_status(&d.link, &status));
}

TEST(HaLinkSession, AnsweredTimeRequestsKeepTheLinkUp) {
  Device d;
  d.rx(kTopicRequest, 0u);
  size_t answered = 0;
  for (uint32_t t = 0; t <= 5000000u; t += 10000u) {
    ha_link_poll(&d.link, t);
    const auto frames = d.tx.frames();
    for (; answered < frames.size(); ++answered) {
      if (frames[answered].first == 10u) d.rx(d.time_reply(100u, 0u), t);
    }
  }
  EXPECT_TRUE(ha_link_connected(&d.link));
  EXPECT_GE(d.link.counters.time_syncs, 9u);
}

TEST(HaLinkSession, TxStopFromTheHostDisconnects) {
  Device d;
  d.rx(kTopicRequest, 0u);
  d.rx({0xFF, 0xFE, 0x00, 0x00, 0xFF, 0x0B, 0x00, 0xF4}, 10u);
  EXPECT_FALSE(ha_link_connected(&d.link));
  EXPECT_EQ(d.link.counters.tx_stops, 1u);
}

TEST(HaLinkSession, LogGoesOutAsRosserialLogOnTopicSeven) {
  Device d;
  d.rx(kTopicRequest, 0u);
  d.tx.bytes.clear();
  ASSERT_TRUE(ha_link_log(&d.link, ROSSERIAL_MSGS_LOG_WARN, "pitot stale"));
  Bytes expected{2};
  link_test::put_str(expected, "pitot stale");
  const auto frames = d.tx.frames();
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].first, 7u);
  EXPECT_EQ(frames[0].second, expected);
}

TEST(HaLinkSession, ParameterRequestAndReplyFollowRequestParam) {
  Device d;
  d.rx(kTopicRequest, 0u);
  d.tx.bytes.clear();
  ASSERT_TRUE(ha_link_request_param(&d.link, "~rate_hz"));
  Bytes request;
  link_test::put_str(request, "~rate_hz");
  ASSERT_EQ(d.tx.frames().at(0), std::make_pair(uint16_t{6}, request));
  Bytes reply;  // int32[] ints = {100}, float32[] floats = {}, string[] strings = {}
  link_test::put_u32(reply, 1);
  link_test::put_u32(reply, 100);
  link_test::put_u32(reply, 0);
  link_test::put_u32(reply, 0);
  d.rx(frame(6, reply), 10u);
  EXPECT_EQ(d.param_ints, std::vector<int32_t>{100});
}

TEST(HaLinkSession, OperatorRequestIsHandedOver) {
  Device d;
  Bytes p = link_test::operator_fields(2, 77);  // SELECT_HA
  p.resize(p.size() + 24, 0);                   // SET_HOME's latitude, longitude, altitude (unused)
  d.rx(frame(101, link_test::sealed_operator_payload(p)), 0u);
  EXPECT_EQ(d.operator_requests, std::vector<uint8_t>{2});
  EXPECT_EQ(d.link.counters.operator_commands, 1u);
}

TEST(HaLinkSession, OperatorRequestWhoseBytesChangedUnderItsCrcIsCountedAndNeverHandedOver) {
  Device d;
  Bytes p = link_test::operator_fields(2, 77);  // SELECT_HA
  p.resize(p.size() + 24, 0);                   // SET_HOME's latitude, longitude, altitude (unused)
  Bytes sealed = link_test::sealed_operator_payload(p);
  sealed[8] -= 1;  // SELECT_HA becomes SELECT_HP ...
  sealed[9] += 1;  // ... and the request id moves by one: rosserial's 8-bit sum still matches
  d.rx(frame(101, sealed), 0u);
  EXPECT_TRUE(d.operator_requests.empty());
  EXPECT_EQ(d.link.counters.operator_bad_crc, 1u);
  EXPECT_EQ(d.link.decoder.counters.frames_ok, 1u);  // the frame itself passed its checksum
  d.rx(frame(101, link_test::sealed_operator_payload(p)), 10u);  // and the link carries on
  EXPECT_EQ(d.operator_requests, std::vector<uint8_t>{2});
}

TEST(HaLinkSession, SetHomeArrivesWithItsPositionInFullPrecision) {
  Device d;
  Bytes p = link_test::operator_fields(5, 78);  // SET_HOME
  for (double v : {40.4237054, -86.9211946, 185.25}) {
    uint8_t raw[8];
    std::memcpy(raw, &v, 8);  // little-endian IEEE 754, as rosserial and the Due lay it out
    p.insert(p.end(), raw, raw + 8);
  }
  d.rx(frame(101, link_test::sealed_operator_payload(p)), 0u);
  ASSERT_EQ(d.operator_requests, std::vector<uint8_t>{5});
  EXPECT_EQ(d.last_operator.request_id, 78u);
  EXPECT_EQ(d.last_operator.use_current, 0);
  EXPECT_EQ(d.last_operator.latitude, 40.4237054);
  EXPECT_EQ(d.last_operator.longitude, -86.9211946);
  EXPECT_EQ(d.last_operator.altitude, 185.25);
}
