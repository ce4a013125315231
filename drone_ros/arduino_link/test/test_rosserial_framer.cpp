// The host framer alone (no ROS): frames as the protocol specifies them, the handshake bytes
// both ways against the Due's side, and every kind of bad input counted and dropped.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "ha_link.h"
#include "rosserial_framer.h"

using arduino_link::encode_frame;
using arduino_link::Frame;
using arduino_link::RosserialFramer;
using Bytes = std::vector<uint8_t>;

namespace {

// Built from the protocol description, independently of both encoders.
Bytes spec_frame(uint16_t topic, const Bytes &payload) {
  const unsigned len = static_cast<unsigned>(payload.size());
  Bytes f{0xFF, 0xFE, static_cast<uint8_t>(len & 0xFF), static_cast<uint8_t>(len >> 8)};
  f.push_back(static_cast<uint8_t>(255 - ((f[2] + f[3]) % 256)));
  f.push_back(static_cast<uint8_t>(topic & 0xFF));
  f.push_back(static_cast<uint8_t>(topic >> 8));
  unsigned sum = f[5] + f[6];
  for (uint8_t b : payload) sum += b;
  f.insert(f.end(), payload.begin(), payload.end());
  f.push_back(static_cast<uint8_t>(255 - (sum % 256)));
  return f;
}

struct Host {
  RosserialFramer framer{1024, 0.05};
  std::vector<Frame> frames;
  void feed(const Bytes &b, double t = 0.0) { framer.feed(b.data(), b.size(), t, &frames); }
};

const Bytes kPayload{0x10, 0xFF, 0xFE, 0x00, 0x7F};  // sync-like bytes inside the payload

}  // namespace

TEST(HostFramer, DocumentedHostFramesAreByteExact) {
  EXPECT_EQ(arduino_link::topic_request_frame(),
            (Bytes{0xFF, 0xFE, 0x00, 0x00, 0xFF, 0x00, 0x00, 0xFF}));
  EXPECT_EQ(arduino_link::tx_stop_frame(), (Bytes{0xFF, 0xFE, 0x00, 0x00, 0xFF, 0x0B, 0x00, 0xF4}));
  EXPECT_EQ(encode_frame(125, kPayload.data(), kPayload.size()), spec_frame(125, kPayload));
}

TEST(HostFramer, HandshakeBothWaysWithTheDueSide) {
  // Host -> device: the topic request. Device -> host: TopicInfo per topic, then a time request.
  struct Wire {
    Bytes bytes;
  } wire;
  HaLinkCallbacks cb{};
  cb.write = [](void *ctx, const uint8_t *d, size_t n) {
    auto *w = static_cast<Wire *>(ctx);
    w->bytes.insert(w->bytes.end(), d, d + n);
  };
  cb.ctx = &wire;
  static HaLink link;
  ha_link_init(&link, &cb);
  const Bytes request = arduino_link::topic_request_frame();
  ha_link_receive(&link, request.data(), request.size(), 0u);
  Host host;
  host.feed(wire.bytes);
  ASSERT_EQ(host.frames.size(),
            6u);  // pwm, decision_status, home; servo_op, operator_command; time
  EXPECT_EQ(host.frames[0].topic_id, 0u);
  EXPECT_EQ(host.frames[2].topic_id, 0u);
  EXPECT_EQ(host.frames[3].topic_id, 1u);
  EXPECT_EQ(host.frames[5].topic_id, 10u);
  // TopicInfo starts with the uint16 topic id, then the topic name as a ROS string.
  const Bytes &info = host.frames[3].payload;
  EXPECT_EQ(info[0] | info[1] << 8, 100);
  EXPECT_EQ(std::string(info.begin() + 6, info.begin() + 14), "servo_op");
  // And the host's time reply is accepted by the device.
  const Bytes reply = spec_frame(10, Bytes{1, 0, 0, 0, 0, 0, 0, 0});
  ha_link_receive(&link, reply.data(), reply.size(), 1000u);
  EXPECT_EQ(link.counters.time_syncs, 1u);
}

TEST(HostFramer, EveryFrameTheDueEncodesIsReadWhole) {
  uint8_t out[300];
  Bytes payload(200);
  for (size_t i = 0; i < payload.size(); ++i) payload[i] = static_cast<uint8_t>(i * 37);
  const size_t n = ha_link_encode_frame(126, payload.data(), payload.size(), out, sizeof out);
  Host host;
  host.feed(Bytes(out, out + n));
  ASSERT_EQ(host.frames.size(), 1u);
  EXPECT_EQ(host.frames[0].topic_id, 126u);
  EXPECT_EQ(host.frames[0].payload, payload);
}

TEST(HostFramer, GarbageBetweenFramesIsCountedAndSkipped) {
  Host host;
  Bytes stream = spec_frame(125, kPayload);
  for (uint8_t g : {0x00, 0x41, 0x42, 0xFE}) stream.push_back(g);
  const Bytes second = spec_frame(126, kPayload);
  stream.insert(stream.end(), second.begin(), second.end());
  host.feed(stream);
  ASSERT_EQ(host.frames.size(), 2u);
  EXPECT_EQ(host.framer.counters().bytes_skipped, 4u);
}

TEST(HostFramer, FramesSplitAtEveryPossibleBoundaryArriveWhole) {
  const Bytes f = spec_frame(125, kPayload);
  for (size_t cut = 1; cut < f.size(); ++cut) {
    Host host;
    host.feed(Bytes(f.begin(), f.begin() + static_cast<long>(cut)));
    host.feed(Bytes(f.begin() + static_cast<long>(cut), f.end()));
    ASSERT_EQ(host.frames.size(), 1u) << cut;
    EXPECT_EQ(host.frames[0].payload, kPayload);
  }
}

TEST(HostFramer, WrongChecksumAbsurdLengthAndBadLengthChecksumAreCounted) {
  Host host;
  const Bytes plain{1, 2, 3, 4};  // no sync-like bytes: the framer must not resync inside it
  Bytes bad_sum = spec_frame(125, plain);
  bad_sum.back() ^= 0x80;
  Bytes bad_len = spec_frame(125, plain);
  bad_len[4] ^= 0x01;
  const Bytes absurd{0xFF, 0xFE, 0xFF, 0xFF, 0x01, 125, 0};  // 65535 with a valid length checksum
  for (const Bytes *b : std::vector<const Bytes *>{&bad_sum, &bad_len, &absurd}) host.feed(*b);
  host.feed(spec_frame(125, plain));
  EXPECT_EQ(host.frames.size(), 1u);
  EXPECT_EQ(host.framer.counters().bad_checksum, 1u);
  EXPECT_EQ(host.framer.counters().bad_length_checksum, 1u);
  EXPECT_EQ(host.framer.counters().oversized, 1u);
}

TEST(HostFramer, StalledFrameIsDroppedAfterTheTimeout) {
  Host host;
  const Bytes f = spec_frame(125, kPayload);
  host.feed(Bytes(f.begin(), f.begin() + 6), 0.0);
  host.framer.poll(0.2);
  EXPECT_EQ(host.framer.counters().timeouts, 1u);
  host.feed(f, 0.3);
  EXPECT_EQ(host.frames.size(), 1u);
}

TEST(HostFramer, RosserialVersionOneIsRefusedNotMisread) {
  Host host;
  Bytes v1 = spec_frame(125, kPayload);
  v1[1] = 0xFF;
  host.feed(v1);
  EXPECT_TRUE(host.frames.empty());
  EXPECT_GE(host.framer.counters().bad_protocol, 1u);
}

TEST(HostFramer, EverySingleBitFlipIsDroppedAndTheNextFrameArrives) {
  const Bytes good = spec_frame(126, Bytes(68, 0x5A));
  for (size_t i = 0; i < good.size(); ++i) {
    for (int bit = 0; bit < 8; ++bit) {
      Host host;
      Bytes f = good;
      f[i] ^= static_cast<uint8_t>(1u << bit);
      host.feed(f, 0.0);
      EXPECT_TRUE(host.frames.empty()) << i << ":" << bit;
      host.feed(good, 1.0);
      EXPECT_EQ(host.frames.size(), 1u) << i << ":" << bit;
    }
  }
}

int main(int argc, char **argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
