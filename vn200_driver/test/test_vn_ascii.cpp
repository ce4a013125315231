// ASCII protocol: the manual's sentences, checksum variants, register responses, errors.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "vn_ascii.h"
#include "vn_checksum.h"

namespace {

VnAsciiResult parse(const std::string& s, VnAsciiMsg* m) {
  return vn_ascii_parse(s.data(), s.size(), m);
}

TEST(VnAscii, ManualYprExampleDecodesToDegrees) {
  VnAsciiMsg m;
  ASSERT_EQ(VN_ASCII_OK, parse("$VNYPR,+010.071,+000.278,-002.026*60\r\n", &m));
  EXPECT_EQ(VN_ASCII_YPR, m.kind);
  EXPECT_FLOAT_EQ(10.071f, m.ypr_deg[0]);
  EXPECT_FLOAT_EQ(0.278f, m.ypr_deg[1]);
  EXPECT_FLOAT_EQ(-2.026f, m.ypr_deg[2]);
}

TEST(VnAscii, OneFlippedCharacterIsRejectedByTheXorChecksum) {
  VnAsciiMsg m;
  EXPECT_EQ(VN_ASCII_ERR_CHECKSUM, parse("$VNYPR,+010.071,+000.278,-002.036*60\r\n", &m));
  EXPECT_EQ(VN_ASCII_ERR_CHECKSUM, parse("$VNYPR,+010.071,+000.278,-002.026*61\r\n", &m));
}

TEST(VnAscii, Crc16ChecksumIsAccepted) {
  const std::string body = "VNYPR,+010.071,+000.278,-002.026";
  uint16_t crc = vn_crc16(reinterpret_cast<const uint8_t*>(body.data()), body.size());
  char hex[5];
  snprintf(hex, sizeof hex, "%04X", crc);
  VnAsciiMsg m;
  EXPECT_EQ(VN_ASCII_OK, parse("$" + body + "*" + hex + "\r\n", &m));
  hex[3] = hex[3] == '0' ? '1' : '0';
  EXPECT_EQ(VN_ASCII_ERR_CHECKSUM, parse("$" + body + "*" + hex + "\r\n", &m));
}

TEST(VnAscii, XxBypassSkipsTheCheck) {
  VnAsciiMsg m;
  ASSERT_EQ(VN_ASCII_OK, parse("$VNYPR,+001.000,+002.000,+003.000*XX\r\n", &m));
  EXPECT_FLOAT_EQ(3.0f, m.ypr_deg[2]);
}

TEST(VnAscii, InsSolutionLlaDecodesEveryField) {
  const std::string body =
      "VNINS,342123.456789,2170,0206,+123.456,-004.500,+001.250,+37.12345678,-121.98765432,"
      "+0123.456,+010.000,-002.500,+000.125,0.5,2.5,0.15";
  uint8_t x = vn_xor8(reinterpret_cast<const uint8_t*>(body.data()), body.size());
  char ck[3];
  snprintf(ck, sizeof ck, "%02X", x);
  VnAsciiMsg m;
  ASSERT_EQ(VN_ASCII_OK, parse("$" + body + "*" + ck + "\r\n", &m));
  EXPECT_EQ(VN_ASCII_INS_LLA, m.kind);
  EXPECT_DOUBLE_EQ(342123.456789, m.ins.tow_s);
  EXPECT_EQ(2170, m.ins.week);
  EXPECT_EQ(0x0206, m.ins.ins_status);
  EXPECT_FLOAT_EQ(123.456f, m.ins.ypr_deg[0]);
  EXPECT_NEAR(37.12345678, m.ins.lat_deg, 1e-12);
  EXPECT_NEAR(-121.98765432, m.ins.lon_deg, 1e-12);
  EXPECT_NEAR(123.456, m.ins.alt_m, 1e-12);
  EXPECT_FLOAT_EQ(0.125f, m.ins.vel_ned_mps[2]);
  EXPECT_FLOAT_EQ(0.15f, m.ins.vel_unc_mps);
}

TEST(VnAscii, ReadRegisterResponseGivesIdAndFields) {
  VnAsciiMsg m;
  const std::string s = "$VNRRG,01,VN-200T-CR*31\r\n";
  ASSERT_EQ(VN_ASCII_OK, parse(s, &m));
  EXPECT_EQ(VN_ASCII_READ_REG, m.kind);
  EXPECT_EQ(1, m.reg_id);
  ASSERT_EQ(2, m.field_count);
  EXPECT_EQ("VN-200T-CR", s.substr(m.field_off[1], m.field_len[1]));
}

TEST(VnAscii, WriteRegisterEchoOfBinaryOutputGivesItsFields) {
  VnAsciiMsg m;
  const std::string s = "$VNWRG,75,2,8,39,15FB,0618,0100,0600*XX\r\n";
  ASSERT_EQ(VN_ASCII_OK, parse(s, &m));
  EXPECT_EQ(VN_ASCII_WRITE_REG, m.kind);
  EXPECT_EQ(75, m.reg_id);
  uint32_t v = 0;
  ASSERT_TRUE(vn_ascii_field_u32(s.data(), &m, 4, 16, &v));
  EXPECT_EQ(0x15FBu, v);
}

TEST(VnAscii, SensorErrorCarriesItsCode) {
  VnAsciiMsg m;
  ASSERT_EQ(VN_ASCII_OK, parse("$VNERR,03*72\r\n", &m));
  EXPECT_EQ(VN_ASCII_ERROR, m.kind);
  EXPECT_EQ(VN_ERR_INVALID_CHECKSUM, m.error_code);
  ASSERT_EQ(VN_ASCII_OK, parse("$VNERR,0C*XX\r\n", &m));
  EXPECT_EQ(VN_ERR_INSUFFICIENT_BAUD_RATE, m.error_code);
}

// Each sentence the parser refuses, with the error a caller is told and why.
struct Refused {
  const char* sentence;
  VnAsciiResult error;
  const char* why;
};
const Refused kRefused[] = {
    {"VNYPR,1,2,3*XX\r\n", VN_ASCII_ERR_FORMAT, "no $"},
    {"$VNYPR,1,2,3\r\n", VN_ASCII_ERR_FORMAT, "no checksum"},
    {"$*XX\r\n", VN_ASCII_ERR_FORMAT, "no header"},
    {"$VNYPR,1,2,3*6\r\n", VN_ASCII_ERR_CHECKSUM, "a one-digit checksum"},
    {"$VNYPR,1,2,3*G0\r\n", VN_ASCII_ERR_CHECKSUM, "a checksum that is not hex"},
    {"$VNINS,1.0,2170,0206*XX\r\n", VN_ASCII_ERR_FIELDS, "an INS solution short of fields"},
    {"$VNYPR,+1.0,,+3.0*XX\r\n", VN_ASCII_ERR_FIELDS, "an empty field: not guessed"},
    {"$VNYPR,+1.0,abc,+3.0*XX\r\n", VN_ASCII_ERR_FIELDS, "a field that is no number"},
    // Converting would be undefined behaviour, so it is refused.
    {"$VNYPR,+1.0,1e39,+3.0*XX\r\n", VN_ASCII_ERR_FIELDS, "beyond the float range"},
};

TEST(VnAscii, MalformedSentencesAndMissingFieldsAreRejectedNotGuessed) {
  VnAsciiMsg m;
  for (const Refused& r : kRefused) {
    EXPECT_EQ(r.error, parse(r.sentence, &m)) << r.sentence << ": " << r.why;
  }
  EXPECT_EQ(VN_ASCII_ERR_NULL, vn_ascii_parse(nullptr, 4, &m));
  EXPECT_EQ(VN_ASCII_ERR_NULL, vn_ascii_parse("$", 1, nullptr));
  std::string many = "$VNXXX";
  for (int i = 0; i < 40; ++i) many += ",1";
  EXPECT_EQ(VN_ASCII_ERR_FORMAT, parse(many + "*XX\r\n", &m));
}

TEST(VnAscii, UnknownHeadersAreWellFormedButUndecoded) {
  VnAsciiMsg m;
  ASSERT_EQ(VN_ASCII_OK, parse("$VNQTN,+0.1,+0.2,+0.3,+0.9*XX\r\n", &m));
  EXPECT_EQ(VN_ASCII_UNKNOWN, m.kind);
  EXPECT_STREQ("VNQTN", m.header);
  EXPECT_EQ(4, m.field_count);
}

TEST(VnNumbers, DecimalParserMatchesTheSensorsFormats) {
  double d = 0;
  ASSERT_TRUE(vn_parse_f64("+010.071", 8, &d));
  EXPECT_DOUBLE_EQ(10.071, d);
  ASSERT_TRUE(vn_parse_f64("-1.5E+02", 8, &d));
  EXPECT_DOUBLE_EQ(-150.0, d);
  ASSERT_TRUE(vn_parse_f64(".5", 2, &d));
  EXPECT_DOUBLE_EQ(0.5, d);
  EXPECT_FALSE(vn_parse_f64("", 0, &d));
  EXPECT_FALSE(vn_parse_f64("+", 1, &d));
  EXPECT_FALSE(vn_parse_f64("1.2.3", 5, &d));
  EXPECT_FALSE(vn_parse_f64("1e", 2, &d));
  EXPECT_FALSE(vn_parse_f64("1e9999", 6, &d));
  EXPECT_FALSE(vn_parse_f64("9e305", 5, &d));  // would scale to infinity
  EXPECT_FALSE(vn_parse_f64("1e21", 4, &d));   // beyond any value the sensor sends
  ASSERT_TRUE(vn_parse_f64("1.5e20", 6, &d));
  EXPECT_DOUBLE_EQ(1.5e20, d);
  uint32_t u = 0;
  ASSERT_TRUE(vn_parse_u32("FFFFFFFF", 8, 16, &u));
  EXPECT_EQ(0xFFFFFFFFu, u);
  EXPECT_FALSE(vn_parse_u32("4294967296", 10, 10, &u));
  EXPECT_FALSE(vn_parse_u32("12a", 3, 10, &u));
}

}  // namespace
