// Command builders: the exact sentences put on the wire, and refusal of what the sensor refuses.
#include <gtest/gtest.h>

#include <string>

#include "output_config.h"
#include "vn_ascii.h"
#include "vn_command.h"

namespace {

std::string build(size_t n, const char* buf) { return std::string(buf, n); }

TEST(VnCommand, AsyncOffMatchesTheManualSentence) {
  char buf[VN_CMD_MAX];
  EXPECT_EQ("$VNWRG,06,0*6C\r\n", build(vn_cmd_async_off(buf, sizeof buf, VN_CK_XOR8), buf));
}

TEST(VnCommand, ReadModelRegister) {
  char buf[VN_CMD_MAX];
  size_t n = vn_cmd_read_register(buf, sizeof buf, VN_REG_MODEL, VN_CK_XOR8);
  EXPECT_EQ("$VNRRG,01*", build(n, buf).substr(0, 10));
  EXPECT_TRUE(vn_ascii_checksum_ok(buf, n));
}

TEST(VnCommand, BaudChangeOnlyForRatesTheSensorSupports) {
  char buf[VN_CMD_MAX];
  size_t n = vn_cmd_set_baud(buf, sizeof buf, 921600, VN_CK_CRC16);
  ASSERT_GT(n, 0u);
  EXPECT_EQ("$VNWRG,05,921600*", build(n, buf).substr(0, 17));
  EXPECT_EQ(n, 17u + 4u + 2u);  // four hex digits of CRC, then CR LF
  EXPECT_TRUE(vn_ascii_checksum_ok(buf, n));
  EXPECT_EQ(0u, vn_cmd_set_baud(buf, sizeof buf, 100000, VN_CK_XOR8));
}

// The HP's default: Binary Output 2 (register 76) routed to port 2 only, so Binary Output 1,
// which feeds the HA on port 1, is never rewritten by the untrusted side.
TEST(VnCommand, NodeWritesBinaryOutputTwoRoutedToItsOwnPortOnly) {
  char buf[VN_CMD_MAX];
  VnBinaryOutputConfig cfg = vn200::node_output_config(100, VN_ASYNC_PORT2, 2);
  size_t n = vn_cmd_binary_output(buf, sizeof buf, &cfg, VN_CK_XOR8);
  std::string s = build(n, buf);
  EXPECT_EQ("$VNWRG,76,2,8,39,15FB,0618,0100,0600*", s.substr(0, 37));
  EXPECT_TRUE(vn_ascii_checksum_ok(buf, n));
  VnAsciiMsg m;
  ASSERT_EQ(VN_ASCII_OK, vn_ascii_parse(buf, n, &m));
  EXPECT_EQ(76, m.reg_id);
}

TEST(VnCommand, BinaryOutputRegistersSeventySixAndSeventySeven) {
  char buf[VN_CMD_MAX];
  VnBinaryOutputConfig cfg{};
  cfg.output = 3;
  cfg.async_mode = VN_ASYNC_PORT1;
  cfg.rate_divisor = 16;
  cfg.groups = VN_GROUP_COMMON;
  cfg.masks[0] = VN_COMMON_YPR;
  size_t n = vn_cmd_binary_output(buf, sizeof buf, &cfg, VN_CK_XOR8);
  EXPECT_EQ("$VNWRG,77,1,16,01,0008*", build(n, buf).substr(0, 23));
  cfg.output = 2;
  n = vn_cmd_binary_output(buf, sizeof buf, &cfg, VN_CK_XOR8);
  EXPECT_EQ("$VNWRG,76,", build(n, buf).substr(0, 10));
}

TEST(VnCommand, ConfigurationsTheSensorWouldRefuseAreNotBuilt) {
  char buf[VN_CMD_MAX];
  VnBinaryOutputConfig good = vn200::node_output_config(50, VN_ASYNC_PORT1, 1);
  ASSERT_GT(vn_cmd_binary_output(buf, sizeof buf, &good, VN_CK_XOR8), 0u);
  VnBinaryOutputConfig c = good;
  c.output = 4;
  EXPECT_EQ(0u, vn_cmd_binary_output(buf, sizeof buf, &c, VN_CK_XOR8));
  c = good;
  c.rate_divisor = 0;
  EXPECT_EQ(0u, vn_cmd_binary_output(buf, sizeof buf, &c, VN_CK_XOR8));
  c = good;
  c.masks[1] = 1;  // field mask for a group not selected
  EXPECT_EQ(0u, vn_cmd_binary_output(buf, sizeof buf, &c, VN_CK_XOR8));
  c = good;
  c.masks[0] |= 0x8000;  // extension bit: undocumented on the VN-200
  EXPECT_EQ(0u, vn_cmd_binary_output(buf, sizeof buf, &c, VN_CK_XOR8));
  c = good;
  c.async_mode = 4;
  EXPECT_EQ(0u, vn_cmd_binary_output(buf, sizeof buf, &c, VN_CK_XOR8));
  EXPECT_EQ(0u, vn_cmd_binary_output(buf, 20, &good, VN_CK_XOR8));  // buffer too small
  EXPECT_EQ(0u, vn_cmd_binary_output(nullptr, 100, &good, VN_CK_XOR8));
}

TEST(VnCommand, OutputRateMustDivideTheImuRate) {
  EXPECT_TRUE(vn200::rate_supported(800));
  EXPECT_TRUE(vn200::rate_supported(100));
  EXPECT_TRUE(vn200::rate_supported(1));
  EXPECT_FALSE(vn200::rate_supported(0));
  EXPECT_FALSE(vn200::rate_supported(300));
  EXPECT_FALSE(vn200::rate_supported(1600));
}

}  // namespace
