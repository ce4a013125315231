// The configuration conversation, driven with the sensor's replies as bytes.
#include <gtest/gtest.h>

#include <string>

#include "output_config.h"
#include "sensor_session.h"
#include "vn_packet_builder.h"

namespace {

using vn200::SensorSession;

SensorSession::Options options() {
  SensorSession::Options o;
  o.output = vn200::node_output_config(100, VN_ASYNC_PORT2, 2);
  return o;
}

void feed(SensorSession& s, const std::string& text, double now) {
  s.on_bytes(reinterpret_cast<const uint8_t*>(text.data()), text.size(), now);
}

std::string echo(const std::string& cmd) {
  // The sensor answers a register write by echoing it (same fields, same checksum).
  return cmd;
}

TEST(SensorSession, ConfiguresAsyncOffThenBinaryOutputAndThenStreams) {
  SensorSession s(options());
  int packets = 0;
  s.on_binary = [&](const VnBinaryData& d, double) {
    ++packets;
    EXPECT_FLOAT_EQ(42.0f, d.ypr_deg[0]);
  };
  s.start(0.0);
  std::string c1 = s.poll_command(0.0);
  EXPECT_EQ("$VNWRG,06,0*6C\r\n", c1);
  EXPECT_EQ("", s.poll_command(0.1));  // waiting for the echo
  feed(s, echo(c1), 0.1);
  std::string c2 = s.poll_command(0.1);
  EXPECT_EQ(0u, c2.rfind("$VNWRG,76,2,8,39,", 0));
  feed(s, echo(c2), 0.2);
  EXPECT_EQ(SensorSession::State::Configured, s.state());
  std::vector<uint8_t> p = makeNodePacket(42.0f);
  s.on_bytes(p.data(), p.size(), 0.3);
  EXPECT_EQ(1, packets);
}

TEST(SensorSession, SilenceAndErrorsCauseResendsThenFailure) {
  SensorSession s(options());
  s.start(0.0);
  std::string c1 = s.poll_command(0.0);
  EXPECT_EQ(c1, s.poll_command(0.6));  // no echo within the timeout: sent again
  feed(s, "$VNERR,03*72\r\n", 0.7);    // the sensor saw a bad checksum: resend at once
  EXPECT_EQ(1u, s.counters().sensor_errors);
  EXPECT_EQ(VN_ERR_INVALID_CHECKSUM, s.counters().last_sensor_error);
  EXPECT_EQ(c1, s.poll_command(0.7));
  EXPECT_EQ(c1, s.poll_command(1.3));
  EXPECT_EQ("", s.poll_command(1.9));  // fourth attempt unanswered
  EXPECT_EQ(SensorSession::State::Failed, s.state());
}

TEST(SensorSession, GarbageAndCorruptPacketsAreCountedNotFatal) {
  SensorSession s(options());
  int packets = 0;
  s.on_binary = [&](const VnBinaryData&, double) { ++packets; };
  s.start(0.0);
  std::vector<uint8_t> bad = makeNodePacket();
  bad[30] ^= 1;
  std::vector<uint8_t> good = makeNodePacket();
  std::vector<uint8_t> stream = {0x00, 0x42};
  stream.insert(stream.end(), bad.begin(), bad.end());
  stream.insert(stream.end(), good.begin(), good.end());
  s.on_bytes(stream.data(), stream.size(), 1.0);
  EXPECT_EQ(1, packets);
  EXPECT_EQ(1u, s.bad_packets());
  EXPECT_EQ(stream.size(), s.counters().bytes);
}

TEST(SensorSession, RestartAfterReconnectConfiguresAgainAndKeepsCounting) {
  SensorSession s(options());
  s.start(0.0);
  std::vector<uint8_t> bad = makeNodePacket();
  bad[40] ^= 2;
  s.on_bytes(bad.data(), bad.size(), 0.05);
  std::string c1 = s.poll_command(0.0);
  feed(s, c1, 0.1);
  std::string c2 = s.poll_command(0.1);
  feed(s, c2, 0.1);
  ASSERT_EQ(SensorSession::State::Configured, s.state());
  std::vector<uint8_t> half = makeNodePacket();
  s.on_bytes(half.data(), half.size() / 2, 0.2);  // unplugged mid-packet
  s.start(5.0);
  EXPECT_EQ(SensorSession::State::Configuring, s.state());
  EXPECT_EQ(c1, s.poll_command(5.0));
  EXPECT_EQ(1u, s.bad_packets());  // totals survive the reconnect
  // The half packet from before the unplug is gone: a whole packet now decodes on its own.
  int packets = 0;
  s.on_binary = [&](const VnBinaryData&, double) { ++packets; };
  std::vector<uint8_t> good = makeNodePacket();
  s.on_bytes(good.data(), good.size(), 5.1);
  EXPECT_EQ(1, packets);
}

}  // namespace
