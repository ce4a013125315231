// The Due's rosserial framing: frames as the protocol specifies them are accepted, and every
// kind of bad input is counted and dropped without losing the frames that follow.
#include <gtest/gtest.h>

#include <numeric>

#include "ha_link_frame.h"
#include "link_test_util.h"

using link_test::Bytes;
using link_test::frame;

namespace {

struct Rx {
  HaLinkDecoder dec;
  std::vector<std::pair<uint16_t, Bytes>> frames;
  Rx() { ha_link_decoder_init(&dec, 50000u); }
  void feed(const Bytes &bytes, uint32_t now_us = 0u) {
    for (uint8_t b : bytes) {
      HaLinkFrame f;
      ha_link_decoder_push(&dec, b, now_us);
      while (ha_link_decoder_next(&dec, &f)) {
        frames.emplace_back(f.topic_id, Bytes(f.payload, f.payload + f.payload_len));
      }
    }
  }
};

const Bytes kPayload{1, 2, 3, 250, 251, 252};

}  // namespace

TEST(HaLinkFrame, HostTopicRequestBytesFromTheProtocolAreOneEmptyFrameOnTopicZero) {
  Rx rx;
  rx.feed({0xFF, 0xFE, 0x00, 0x00, 0xFF, 0x00, 0x00, 0xFF});
  ASSERT_EQ(rx.frames.size(), 1u);
  EXPECT_EQ(rx.frames[0].first, 0u);
  EXPECT_TRUE(rx.frames[0].second.empty());
}

TEST(HaLinkFrame, EncoderWritesExactlyTheSpecifiedBytes) {
  uint8_t out[64];
  const size_t n = ha_link_encode_frame(125, kPayload.data(), kPayload.size(), out, sizeof out);
  EXPECT_EQ(Bytes(out, out + n), frame(125, kPayload));
  // The documented TX_STOP frame: ff fe 00 00 ff 0b 00 f4.
  const size_t m = ha_link_encode_frame(11, nullptr, 0, out, sizeof out);
  EXPECT_EQ(Bytes(out, out + m), (Bytes{0xFF, 0xFE, 0x00, 0x00, 0xFF, 0x0B, 0x00, 0xF4}));
}

TEST(HaLinkFrame, GarbageBetweenFramesIsCountedAndBothFramesSurvive) {
  Rx rx;
  Bytes stream = frame(100, kPayload);
  const Bytes garbage{0x00, 0x13, 0x37, 0xFE, 0x42};
  stream.insert(stream.end(), garbage.begin(), garbage.end());
  const Bytes second = frame(101, kPayload);
  stream.insert(stream.end(), second.begin(), second.end());
  rx.feed(stream);
  ASSERT_EQ(rx.frames.size(), 2u);
  EXPECT_EQ(rx.frames[1].first, 101u);
  EXPECT_EQ(rx.dec.counters.bytes_skipped, garbage.size());
}

TEST(HaLinkFrame, FrameSplitAcrossManyReadsArrivesWhole) {
  Rx rx;
  const Bytes f = frame(100, kPayload);
  for (size_t i = 0; i < f.size(); ++i) {
    rx.feed(Bytes{f[i]}, static_cast<uint32_t>(i * 1000u));
  }
  ASSERT_EQ(rx.frames.size(), 1u);
  EXPECT_EQ(rx.frames[0].second, kPayload);
}

TEST(HaLinkFrame, WrongChecksumIsCountedAndTheNextFrameStillArrives) {
  Rx rx;
  Bytes bad = frame(100, kPayload);
  bad.back() ^= 0x01;
  rx.feed(bad);
  rx.feed(frame(100, kPayload));
  EXPECT_EQ(rx.frames.size(), 1u);
  EXPECT_EQ(rx.dec.counters.bad_checksum, 1u);
}

TEST(HaLinkFrame, AbsurdLengthWithAValidLengthChecksumIsRefused) {
  Rx rx;
  // length 60000 = 0xEA60: checksum 255 - ((0x60 + 0xEA) % 256) = 0xB5
  rx.feed({0xFF, 0xFE, 0x60, 0xEA, 0xB5, 0x64, 0x00});
  rx.feed(frame(100, kPayload));
  EXPECT_EQ(rx.dec.counters.oversized, 1u);
  EXPECT_EQ(rx.frames.size(), 1u);
}

TEST(HaLinkFrame, BadLengthChecksumIsCounted) {
  Rx rx;
  Bytes f = frame(100, kPayload);
  f[4] ^= 0x10;
  rx.feed(f);
  EXPECT_EQ(rx.dec.counters.bad_length_checksum, 1u);
  EXPECT_TRUE(rx.frames.empty());
}

TEST(HaLinkFrame, ProtocolVersionOneIsRefused) {
  Rx rx;
  Bytes f = frame(100, kPayload);
  f[1] = 0xFF;  // rosserial before Groovy
  rx.feed(f);
  EXPECT_GE(rx.dec.counters.bad_protocol, 1u);
  EXPECT_TRUE(rx.frames.empty());
}

TEST(HaLinkFrame, FrameThatStopsMidwayIsDroppedAfterTheTimeout) {
  Rx rx;
  const Bytes f = frame(100, kPayload);
  rx.feed(Bytes(f.begin(), f.begin() + 9), 0u);
  ha_link_decoder_poll(&rx.dec, 60000u);
  EXPECT_EQ(rx.dec.counters.timeouts, 1u);
  rx.feed(f, 61000u);
  ASSERT_EQ(rx.frames.size(), 1u);
}

TEST(HaLinkFrame, TimeoutHoldsAcrossTheClockWrap) {
  Rx rx;
  const Bytes f = frame(100, kPayload);
  rx.feed(Bytes(f.begin(), f.begin() + 9), 0xFFFFFF00u);
  rx.feed(Bytes(f.begin() + 9, f.end()), 0x00000100u);  // 512 us later
  EXPECT_EQ(rx.frames.size(), 1u);
  EXPECT_EQ(rx.dec.counters.timeouts, 0u);
}

TEST(HaLinkFrame, EverySingleBitFlipIsCaughtAndNoCorruptPayloadIsDelivered) {
  const Bytes good = frame(100, link_test::servo_command_payload(link_test::Cmd{}));
  for (size_t byte = 0; byte < good.size(); ++byte) {
    for (int bit = 0; bit < 8; ++bit) {
      Rx rx;
      Bytes f = good;
      f[byte] ^= static_cast<uint8_t>(1u << bit);
      rx.feed(f);
      ha_link_decoder_poll(&rx.dec, 1000000u);
      const auto &c = rx.dec.counters;
      EXPECT_TRUE(rx.frames.empty()) << "byte " << byte << " bit " << bit;
      EXPECT_GE(c.bytes_skipped + c.bad_protocol + c.bad_length_checksum + c.oversized +
                    c.bad_checksum + c.timeouts,
                1u);
      rx.feed(good, 2000000u);  // and the link carries on
      EXPECT_EQ(rx.frames.size(), 1u);
    }
  }
}

TEST(HaLinkFrame, EncoderRefusesPayloadsAboveTheAnnouncedBuffer) {
  static uint8_t payload[HA_LINK_MAX_PAYLOAD + 1];
  static uint8_t out[HA_LINK_MAX_PAYLOAD + 16];
  EXPECT_EQ(ha_link_encode_frame(100, payload, sizeof payload, out, sizeof out), 0u);
  EXPECT_EQ(ha_link_encode_frame(100, payload, 10, out, 12), 0u);
}

TEST(HaLinkFrame, FramesSwallowedByAFrameWhoseLengthWasCorruptedAreFoundWhenItFails) {
  Rx rx;
  // A header whose length (60) passes its own checksum but is wrong: the two frames behind it
  // are taken as its payload, until its checksum fails; then both are found inside it.
  Bytes stream{0xFF, 0xFE, 60, 0x00, static_cast<uint8_t>(255 - 60), 0x64, 0x00};
  const Bytes a = frame(100, kPayload);
  const Bytes b = frame(101, kPayload);
  stream.insert(stream.end(), a.begin(), a.end());
  stream.insert(stream.end(), b.begin(), b.end());
  while (stream.size() < 7u + 60u + 1u) stream.push_back(0x00);
  if ((std::accumulate(stream.begin() + 5, stream.end() - 1, 0u) + stream.back()) % 256u == 255u) {
    stream.back() = 0x01;  // the corrupt frame's checksum must fail, as it nearly always does
  }
  rx.feed(stream);
  ASSERT_EQ(rx.frames.size(), 2u);
  EXPECT_EQ(rx.frames[0].first, 100u);
  EXPECT_EQ(rx.frames[1].first, 101u);
  EXPECT_EQ(rx.frames[1].second, kPayload);
  EXPECT_EQ(rx.dec.counters.bad_checksum, 1u);
}

TEST(HaLinkFrame, AFrameMissingOneByteDoesNotTakeTheNextFrameWithIt) {
  const Bytes good = frame(100, link_test::servo_command_payload(link_test::Cmd{}));
  for (size_t lost = 0; lost < good.size(); ++lost) {
    Rx rx;
    Bytes damaged = good;
    damaged.erase(damaged.begin() + static_cast<long>(lost));
    rx.feed(damaged, 0u);
    rx.feed(good, 10000u);  // the next period's frame, 10 ms later
    ASSERT_EQ(rx.frames.size(), 1u) << "byte " << lost << " lost";
    EXPECT_EQ(rx.frames[0].second, link_test::servo_command_payload(link_test::Cmd{}));
  }
}
