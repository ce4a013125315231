// Framing a live byte stream: garbage, truncation, corruption, arbitrary read boundaries.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "vn_framer.h"
#include "vn_packet_builder.h"

namespace {

using Bytes = std::vector<uint8_t>;

Bytes ascii(const std::string& s) { return Bytes(s.begin(), s.end()); }
Bytes cat(std::initializer_list<Bytes> parts) {
  Bytes out;
  for (const Bytes& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

// Feeds `stream` in reads of the given sizes (the rest in one read) and returns every frame.
std::vector<Bytes> frames(VnFramer* f, const Bytes& stream, const std::vector<size_t>& reads = {}) {
  std::vector<Bytes> out;
  size_t pos = 0;
  size_t r = 0;
  while (pos <= stream.size()) {
    size_t n = r < reads.size() ? reads[r] : stream.size() - pos;
    n = std::min(n, stream.size() - pos);
    ++r;
    size_t off = 0;
    for (;;) {
      size_t used = 0;
      VnFrame fr;
      int got = vn_framer_next(f, stream.data() + pos + off, n - off, &used, &fr);
      off += used;
      if (!got) break;
      out.emplace_back(fr.data, fr.data + fr.len);
    }
    pos += n;
    if (pos == stream.size()) break;
  }
  return out;
}

const std::string kYpr = "$VNYPR,+010.071,+000.278,-002.026*60\r\n";

TEST(VnFramer, GarbageBeforeAPacketIsCountedAndSkipped) {
  VnFramer f;
  vn_framer_init(&f);
  Bytes pkt = makeNodePacket();
  auto got = frames(&f, cat({Bytes{0x00, 0x13, 0x37, 0xFF, 'a', '\n'}, pkt}));
  ASSERT_EQ(1u, got.size());
  EXPECT_EQ(pkt, got[0]);
  EXPECT_EQ(6u, f.stats.dropped_bytes);
  EXPECT_EQ(0u, vn_framer_bad_packets(&f.stats));
}

TEST(VnFramer, AsciiAndBinaryInterleavedComeOutInOrder) {
  VnFramer f;
  vn_framer_init(&f);
  Bytes a = makeNodePacket(1.0f), b = makeNodePacket(2.0f);
  auto got = frames(&f, cat({ascii(kYpr), a, ascii("$VNERR,03*72\r\n"), b}));
  ASSERT_EQ(4u, got.size());
  EXPECT_EQ(ascii(kYpr), got[0]);
  EXPECT_EQ(a, got[1]);
  EXPECT_EQ(b, got[3]);
  EXPECT_EQ(2u, f.stats.binary_frames);
  EXPECT_EQ(2u, f.stats.ascii_frames);
}

TEST(VnFramer, TruncatedPacketDoesNotHideTheNextOne) {
  VnFramer f;
  vn_framer_init(&f);
  Bytes cut = makeNodePacket(1.0f);
  cut.resize(cut.size() / 2);  // the cable glitched mid-packet
  Bytes good = makeNodePacket(2.0f), after = makeNodePacket(3.0f);
  auto got = frames(&f, cat({cut, good, after}));
  ASSERT_EQ(2u, got.size());
  EXPECT_EQ(good, got[0]);
  EXPECT_EQ(after, got[1]);
  EXPECT_GE(f.stats.bad_binary_crc, 1u);
}

TEST(VnFramer, BadCrcIsCountedAndDropped) {
  VnFramer f;
  vn_framer_init(&f);
  Bytes bad = makeNodePacket();
  bad[20] ^= 0x40;
  Bytes good = makeNodePacket(5.0f);
  auto got = frames(&f, cat({bad, good}));
  ASSERT_EQ(1u, got.size());
  EXPECT_EQ(good, got[0]);
  EXPECT_EQ(1u, f.stats.bad_binary_crc);
}

TEST(VnFramer, AsciiWithWrongChecksumOrBinaryNoiseIsCounted) {
  VnFramer f;
  vn_framer_init(&f);
  Bytes stream = cat({ascii("$VNYPR,+010.071,+000.278,-002.026*61\r\n"), ascii("$VNYPR,+0"),
                      Bytes{0x01, 0x02}, ascii("\r\n"), ascii("$VNYPR\rX\r\n"), ascii(kYpr)});
  auto got = frames(&f, stream);
  ASSERT_EQ(1u, got.size());
  EXPECT_EQ(ascii(kYpr), got[0]);
  EXPECT_EQ(1u, f.stats.bad_ascii_checksum);
  EXPECT_EQ(2u, f.stats.bad_ascii_char);
}

TEST(VnFramer, UndocumentedGroupsOrFieldsResynchronise) {
  VnFramer f;
  vn_framer_init(&f);
  Bytes good = makeNodePacket();
  auto got =
      frames(&f, cat({Bytes{0xFA, 0x80}, Bytes{0xFA, 0x00}, Bytes{0xFA, 0x01, 0x00, 0x80}, good}));
  ASSERT_EQ(1u, got.size());
  EXPECT_EQ(good, got[0]);
  EXPECT_EQ(2u, f.stats.bad_binary_groups);
  EXPECT_EQ(1u, f.stats.bad_binary_field);
}

TEST(VnFramer, PacketsSplitAtEveryByteBoundaryReassemble) {
  Bytes stream =
      cat({ascii(kYpr), makeNodePacket(1.0f), makeNodePacket(2.0f), ascii("$VNWRG,06,0*6C\r\n")});
  for (size_t split = 0; split <= stream.size(); ++split) {
    VnFramer f;
    vn_framer_init(&f);
    auto got = frames(&f, stream, {split});
    ASSERT_EQ(4u, got.size()) << "split at " << split;
    EXPECT_EQ(0u, f.stats.dropped_bytes);
  }
}

TEST(VnFramer, ByteAtATimeMatchesOneBigRead) {
  Bytes stream = cat({Bytes{1, 2, 3}, makeNodePacket(1.0f), ascii(kYpr), makeNodePacket(2.0f)});
  VnFramer a, b;
  vn_framer_init(&a);
  vn_framer_init(&b);
  auto whole = frames(&a, stream);
  auto bytewise = frames(&b, stream, std::vector<size_t>(stream.size(), 1));
  EXPECT_EQ(whole, bytewise);
  EXPECT_EQ(3u, whole.size());
}

TEST(VnFramer, LargestBinaryPacketPasses) {
  std::vector<uint16_t> masks;
  size_t payload = 0;
  for (unsigned g = 0; g < 6; ++g) {
    uint16_t m = 0;
    for (unsigned bit = 0; bit < 16; ++bit)
      if (vn_bin_field_size(g, bit)) {
        m = static_cast<uint16_t>(m | (1u << bit));
        payload += vn_bin_field_size(g, bit);
      }
    masks.push_back(m);
  }
  VnPacketBuilder b(0x3F, masks);
  for (size_t i = 0; i < payload; ++i) b.u8(static_cast<uint8_t>(i));
  Bytes big = b.finish();
  ASSERT_EQ(static_cast<size_t>(VN_FRAME_MAX), big.size());
  VnFramer f;
  vn_framer_init(&f);
  auto got = frames(&f, cat({big, makeNodePacket()}));
  ASSERT_EQ(2u, got.size());
  EXPECT_EQ(big, got[0]);
}

TEST(VnFramer, OverlongAsciiIsCutOffAndTheStreamRecovers) {
  VnFramer f;
  vn_framer_init(&f);
  std::string endless = "$VNYPR," + std::string(400, '1');
  Bytes good = makeNodePacket();
  auto got = frames(&f, cat({ascii(endless), good, ascii(kYpr)}));
  ASSERT_EQ(2u, got.size());
  EXPECT_EQ(good, got[0]);
  EXPECT_EQ(1u, f.stats.bad_ascii_too_long);
}

TEST(VnFramer, AsciiAtTheLengthLimitPassesAndOneMoreByteDoesNot) {
  // VN_ASCII_MAX counts "$" through CRLF.
  std::string at_limit = "$VNXYZ," + std::string(VN_ASCII_MAX - 7 - 5, '7') + "*XX\r\n";
  ASSERT_EQ(static_cast<size_t>(VN_ASCII_MAX), at_limit.size());
  VnFramer f;
  vn_framer_init(&f);
  EXPECT_EQ(1u, frames(&f, ascii(at_limit)).size());
  std::string over = "$VNXYZ," + std::string(VN_ASCII_MAX - 7 - 4, '7') + "*XX\r\n";
  vn_framer_init(&f);
  EXPECT_EQ(0u, frames(&f, ascii(over)).size());
  EXPECT_EQ(1u, f.stats.bad_ascii_too_long);
}

TEST(VnFramer, NullArgumentsAreRefused) {
  VnFramer f;
  vn_framer_init(&f);
  size_t used = 7;
  VnFrame fr;
  EXPECT_EQ(0, vn_framer_next(nullptr, nullptr, 0, &used, &fr));
  EXPECT_EQ(0u, used);
  EXPECT_EQ(0, vn_framer_next(&f, nullptr, 5, &used, &fr));
  uint8_t b = 0xFA;
  EXPECT_EQ(0, vn_framer_next(&f, &b, 1, nullptr, &fr));
}

}  // namespace
