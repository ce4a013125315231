// Binary output packets built field by field, decoded back; CRC against an independent bitwise
// implementation; every group combination; the largest packet.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "output_config.h"
#include "vn_binary.h"
#include "vn_checksum.h"
#include "vn_packet_builder.h"

namespace {

// Textbook MSB-first CRC-16 with polynomial 0x1021 and initial value 0, bit by bit.
uint16_t bitwiseCrc(const uint8_t* d, size_t n) {
  uint16_t crc = 0;
  for (size_t i = 0; i < n; ++i) {
    crc ^= static_cast<uint16_t>(d[i] << 8);
    for (int b = 0; b < 8; ++b) {
      crc = (crc & 0x8000) ? static_cast<uint16_t>((crc << 1) ^ 0x1021)
                           : static_cast<uint16_t>(crc << 1);
    }
  }
  return crc;
}

TEST(VnCrc, MatchesTheCcittCheckValueAndABitwiseReference) {
  const std::string check = "123456789";
  EXPECT_EQ(0x31C3, vn_crc16(reinterpret_cast<const uint8_t*>(check.data()), check.size()));
  uint8_t data[300];
  for (size_t i = 0; i < sizeof data; ++i) data[i] = static_cast<uint8_t>(i * 37 + 11);
  for (size_t n = 0; n <= sizeof data; n += 7) EXPECT_EQ(bitwiseCrc(data, n), vn_crc16(data, n));
}

TEST(VnBinary, NodePacketDecodesEveryFieldInUnits) {
  std::vector<uint8_t> p = makeNodePacket();
  VnBinaryOutputConfig cfg = vn200::node_output_config(100, VN_ASYNC_PORT2, 2);
  ASSERT_EQ(vn_binary_output_packet_len(&cfg), p.size());
  VnBinaryData d;
  ASSERT_EQ(VN_BIN_OK, vn_bin_decode(p.data(), p.size(), &d));
  EXPECT_EQ(1234567890123ull, d.time_startup_ns);
  EXPECT_EQ(1370000000123456789ull, d.time_gps_ns);
  EXPECT_FLOAT_EQ(123.5f, d.ypr_deg[0]);
  EXPECT_FLOAT_EQ(1.25f, d.ypr_deg[2]);
  EXPECT_FLOAT_EQ(0.927362f, d.quat_xyzw[3]);
  EXPECT_FLOAT_EQ(-0.02f, d.angular_rate_radps[1]);
  EXPECT_DOUBLE_EQ(37.12345678, d.lat_deg);
  EXPECT_DOUBLE_EQ(-121.98765432, d.lon_deg);
  EXPECT_DOUBLE_EQ(123.456, d.alt_m);
  EXPECT_FLOAT_EQ(0.125f, d.vel_ned_mps[2]);
  EXPECT_FLOAT_EQ(-9.81f, d.accel_mps2[2]);
  EXPECT_FLOAT_EQ(0.45f, d.mag_gauss[2]);
  EXPECT_FLOAT_EQ(31.5f, d.temp_c);
  EXPECT_FLOAT_EQ(101.325f, d.pressure_kpa);
  EXPECT_EQ(0x0206, d.ins_status);
  EXPECT_EQ(9, d.num_sats);
  EXPECT_EQ(3, d.gps_fix);
  EXPECT_FLOAT_EQ(3.0f, d.gps_pos_unc_ned_m[2]);
  EXPECT_FLOAT_EQ(0.2f, d.gps_vel_unc_mps);
  EXPECT_FLOAT_EQ(0.5f, d.ypr_unc_deg[0]);
  EXPECT_FLOAT_EQ(2.5f, d.ins_pos_unc_m);
  EXPECT_FLOAT_EQ(0.15f, d.ins_vel_unc_mps);
  const uint32_t want = VN_HAS_TIME_STARTUP | VN_HAS_TIME_GPS | VN_HAS_YPR | VN_HAS_QUATERNION |
                        VN_HAS_ANGULAR_RATE | VN_HAS_POSITION_LLA | VN_HAS_VEL_NED | VN_HAS_ACCEL |
                        VN_HAS_MAG | VN_HAS_TEMP | VN_HAS_PRESSURE | VN_HAS_INS_STATUS |
                        VN_HAS_NUM_SATS | VN_HAS_GPS_FIX | VN_HAS_YPR_UNC | VN_HAS_INS_POS_UNC |
                        VN_HAS_INS_VEL_UNC | VN_HAS_GPS_POS_UNC | VN_HAS_GPS_VEL_UNC;
  EXPECT_EQ(want, d.has);
}

TEST(VnBinary, CrcIsSentBigEndianOverEverythingAfterTheSync) {
  std::vector<uint8_t> p = makeNodePacket();
  uint16_t crc = bitwiseCrc(p.data() + 1, p.size() - 3);
  EXPECT_EQ(crc >> 8, p[p.size() - 2]);
  EXPECT_EQ(crc & 0xFF, p[p.size() - 1]);
}

TEST(VnBinary, EveryFlippedBitIsCaught) {
  std::vector<uint8_t> p = makeNodePacket();
  VnBinaryData d;
  for (size_t i = 1; i < p.size(); ++i) {
    for (int bit = 0; bit < 8; ++bit) {
      std::vector<uint8_t> q = p;
      q[i] ^= static_cast<uint8_t>(1u << bit);
      EXPECT_NE(VN_BIN_OK, vn_bin_decode(q.data(), q.size(), &d)) << "byte " << i << " bit " << bit;
    }
  }
}

TEST(VnBinary, TruncatedAndOverlongPacketsAreRejected) {
  std::vector<uint8_t> p = makeNodePacket();
  VnBinaryData d;
  for (size_t n = 0; n < p.size(); ++n) EXPECT_NE(VN_BIN_OK, vn_bin_decode(p.data(), n, &d));
  std::vector<uint8_t> longer = p;
  longer.push_back(0);
  EXPECT_EQ(VN_BIN_ERR_LENGTH, vn_bin_decode(longer.data(), longer.size(), &d));
  EXPECT_EQ(VN_BIN_ERR_NULL, vn_bin_decode(nullptr, 10, &d));
}

TEST(VnBinary, UndocumentedGroupsAndFieldsAreRejected) {
  VnBinaryData d;
  std::vector<uint8_t> g7 = VnPacketBuilder(0x40, {0x0001}).zeros(8).finish();
  EXPECT_EQ(VN_BIN_ERR_GROUPS, vn_bin_decode(g7.data(), g7.size(), &d));
  std::vector<uint8_t> none = VnPacketBuilder(0x00, {}).zeros(4).finish();
  EXPECT_EQ(VN_BIN_ERR_GROUPS, vn_bin_decode(none.data(), none.size(), &d));
  std::vector<uint8_t> ext = VnPacketBuilder(0x01, {0x8000}).zeros(8).finish();
  EXPECT_EQ(VN_BIN_ERR_FIELD, vn_bin_decode(ext.data(), ext.size(), &d));
  std::vector<uint8_t> reserved_time = VnPacketBuilder(0x02, {0x0400}).zeros(8).finish();
  EXPECT_EQ(VN_BIN_ERR_FIELD, vn_bin_decode(reserved_time.data(), reserved_time.size(), &d));
}

uint16_t fullMask(unsigned g) {
  uint16_t m = 0;
  for (unsigned b = 0; b < 16; ++b)
    if (vn_bin_field_size(g, b)) m = static_cast<uint16_t>(m | (1u << b));
  return m;
}

TEST(VnBinary, EveryGroupCombinationDecodesToItsDocumentedLength) {
  for (unsigned groups = 1; groups < 64; ++groups) {
    for (int full = 0; full < 2; ++full) {
      VnBinaryOutputConfig node = vn200::node_output_config(100, VN_ASYNC_PORT2, 2);
      std::vector<uint16_t> masks;
      size_t payload = 0;
      for (unsigned g = 0; g < 6; ++g) {
        if (!(groups & (1u << g))) continue;
        // The node's own mask where it selects the group, else the first field, or all fields.
        uint16_t m = full ? fullMask(g) : (node.masks[g] ? node.masks[g] : uint16_t{1});
        masks.push_back(m);
        for (unsigned b = 0; b < 16; ++b)
          if (m & (1u << b)) payload += vn_bin_field_size(g, b);
      }
      VnPacketBuilder b(static_cast<uint8_t>(groups), masks);
      // Bytes below 0x40 keep every float exponent finite (NaN/inf packets are refused).
      for (size_t i = 0; i < payload; ++i) b.u8(static_cast<uint8_t>((i * 13) & 0x3F));
      std::vector<uint8_t> p = b.finish();
      EXPECT_EQ(p.size(),
                vn_bin_packet_len(static_cast<uint8_t>(groups), masks.data(), masks.size()));
      VnBinaryData d;
      EXPECT_EQ(VN_BIN_OK, vn_bin_decode(p.data(), p.size(), &d)) << "groups " << groups;
      EXPECT_EQ(groups, d.groups);
    }
  }
}

TEST(VnBinary, NanOrInfinityInAUsedFieldRejectsThePacket) {
  VnBinaryData d;
  std::vector<uint8_t> nan_yaw =
      VnPacketBuilder(VN_GROUP_COMMON, {VN_COMMON_YPR}).f32(std::nanf("")).f32(1).f32(2).finish();
  EXPECT_EQ(VN_BIN_ERR_NONFINITE, vn_bin_decode(nan_yaw.data(), nan_yaw.size(), &d));
  EXPECT_EQ(0u, d.has);
  std::vector<uint8_t> inf_lat =
      VnPacketBuilder(VN_GROUP_INS, {VN_INS_POS_LLA}).f64(HUGE_VAL).f64(1).f64(2).finish();
  EXPECT_EQ(VN_BIN_ERR_NONFINITE, vn_bin_decode(inf_lat.data(), inf_lat.size(), &d));
  std::vector<uint8_t> fine = VnPacketBuilder(VN_GROUP_COMMON, {VN_COMMON_YPR})
                                  .f32(-0.0f)
                                  .f32(1e-40f)
                                  .f32(3.4e38f)
                                  .finish();
  EXPECT_EQ(VN_BIN_OK, vn_bin_decode(fine.data(), fine.size(), &d));
}

TEST(VnBinary, LargestDocumentedPacketFitsTheBuffers) {
  EXPECT_EQ(static_cast<size_t>(VN_BIN_MAX_PACKET), vn_bin_max_packet_len());
}

TEST(VnBinary, TimeAndImuGroupsDecodeToo) {
  VnPacketBuilder b(VN_GROUP_TIME | VN_GROUP_IMU,
                    {VN_TIME_GPS_TOW | VN_TIME_GPS_WEEK,
                     VN_IMU_TEMP | VN_IMU_PRES | VN_IMU_ACCEL | VN_IMU_ANGULAR_RATE});
  b.u64(345600123456789ull).u16(2170).f32(25.0f).f32(99.5f);
  b.f32(1).f32(2).f32(3).f32(0.1f).f32(0.2f).f32(0.3f);
  std::vector<uint8_t> p = b.finish();
  VnBinaryData d;
  ASSERT_EQ(VN_BIN_OK, vn_bin_decode(p.data(), p.size(), &d));
  EXPECT_EQ(345600123456789ull, d.gps_tow_ns);
  EXPECT_EQ(2170, d.gps_week);
  EXPECT_FLOAT_EQ(99.5f, d.pressure_kpa);
  EXPECT_FLOAT_EQ(3.0f, d.accel_mps2[2]);
  EXPECT_FLOAT_EQ(0.3f, d.angular_rate_radps[2]);
}

}  // namespace
