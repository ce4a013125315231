// Every field of every binary group, each set to its own value, decoded and checked member by
// member and byte by byte: which field lands in which member of VnBinaryData, which presence bits
// it sets, which fields are skipped, and which group wins when two carry the same quantity. The
// layouts below are the manual's (VN-200 User Manual, binary group tables), written here
// independently of the decoder's table.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "vn_binary.h"
#include "vn_packet_builder.h"

namespace {

// One run of same-typed elements inside a field: Q u64, I u32, H u16, B u8, f float, d double.
struct Part {
  char kind;
  unsigned count;
};
using Field = std::vector<Part>;  // empty: the manual defines no field at this bit

// clang-format off
const std::vector<Field> kLayout[VN_BIN_GROUP_COUNT] = {
    // Common: TimeStartup, TimeGps, TimeSyncIn, YPR, Quaternion, AngularRate, Position (LLA),
    // Velocity (NED), Accel, Imu (accel, gyro), MagPres (mag[3], temp, pres), DeltaTheta (dt,
    // dtheta[3], dvel[3]), InsStatus, SyncInCnt, TimeGpsPps
    {{{'Q', 1}}, {{'Q', 1}}, {{'Q', 1}}, {{'f', 3}}, {{'f', 4}}, {{'f', 3}}, {{'d', 3}},
     {{'f', 3}}, {{'f', 3}}, {{'f', 6}}, {{'f', 5}}, {{'f', 7}}, {{'H', 1}}, {{'I', 1}},
     {{'Q', 1}}},
    // Time: TimeStartup, TimeGps, GpsTow, GpsWeek, TimeSyncIn, TimeGpsPps, TimeUTC (year ...
    // ms), SyncInCnt, SyncOutCnt, TimeStatus
    {{{'Q', 1}}, {{'Q', 1}}, {{'Q', 1}}, {{'H', 1}}, {{'Q', 1}}, {{'Q', 1}},
     {{'B', 6}, {'H', 1}}, {{'I', 1}}, {{'I', 1}}, {{'B', 1}}},
    // IMU: ImuStatus, UncompMag, UncompAccel, UncompGyro, Temp, Pres, DeltaTheta (dt,
    // dtheta[3]), DeltaVel, Mag, Accel, AngularRate
    {{{'H', 1}}, {{'f', 3}}, {{'f', 3}}, {{'f', 3}}, {{'f', 1}}, {{'f', 1}}, {{'f', 4}},
     {{'f', 3}}, {{'f', 3}}, {{'f', 3}}, {{'f', 3}}},
    // GPS: UTC, Tow, Week, NumSats, Fix, PosLla, PosEcef, VelNed, VelEcef, PosU, VelU, TimeU
    {{{'B', 6}, {'H', 1}}, {{'Q', 1}}, {{'H', 1}}, {{'B', 1}}, {{'B', 1}}, {{'d', 3}},
     {{'d', 3}}, {{'f', 3}}, {{'f', 3}}, {{'f', 3}}, {{'f', 1}}, {{'I', 1}}},
    // Attitude: VpeStatus, YPR, Quaternion, DCM, MagNed, AccelNed, LinearAccelBody,
    // LinearAccelNed, YprU
    {{{'H', 1}}, {{'f', 3}}, {{'f', 4}}, {{'f', 9}}, {{'f', 3}}, {{'f', 3}}, {{'f', 3}},
     {{'f', 3}}, {{'f', 3}}},
    // INS: InsStatus, PosLla, PosEcef, VelBody, VelNed, VelEcef, MagEcef, AccelEcef,
    // LinearAccelEcef, PosU, VelU
    {{{'H', 1}}, {{'d', 3}}, {{'d', 3}}, {{'f', 3}}, {{'f', 3}}, {{'f', 3}}, {{'f', 3}},
     {{'f', 3}}, {{'f', 3}}, {{'f', 1}}, {{'f', 1}}},
};
// clang-format on

// A value of its own for element i of field (g, b), using every byte of its type, so a field
// stored in the wrong member, at the wrong width or in the wrong byte order shows.
uint64_t u64v(unsigned g, unsigned b, unsigned i) {
  return 0x8877665544000000ull + (uint64_t{g} << 16) + (uint64_t{b} << 8) + i;
}
uint32_t u32v(unsigned g, unsigned b, unsigned i) { return 0x44330000u + (g << 12) + (b << 4) + i; }
uint16_t u16v(unsigned g, unsigned b, unsigned i) {
  return static_cast<uint16_t>(0x8000u + (g << 10) + (b << 5) + i);
}
uint8_t u8v(unsigned g, unsigned b, unsigned i) { return static_cast<uint8_t>(16u * g + b + i); }
// Odd elements negative; the fraction is exact in binary, so every value is distinct and exact.
float f32v(unsigned g, unsigned b, unsigned i) {
  const float v = static_cast<float>(1000u * g + 20u * b + i) + 0.375f;
  return (i % 2u) ? -v : v;
}
// Needs all 53 bits: a double stored through a float would lose the tail.
double f64v(unsigned g, unsigned b, unsigned i) {
  return static_cast<double>(1000u * g + 20u * b + i) + 0.1234567890123;
}

size_t partBytes(const Part& p) {
  switch (p.kind) {
    case 'Q':
    case 'd':
      return 8u * p.count;
    case 'I':
    case 'f':
      return 4u * p.count;
    case 'H':
      return 2u * p.count;
    default:
      return p.count;
  }
}

uint16_t everyFieldMask(unsigned g) {
  uint16_t m = 0;
  for (size_t b = 0; b < kLayout[g].size(); ++b) m = static_cast<uint16_t>(m | (1u << b));
  return m;
}

// The packet with the groups in `groups`, every field of each set to its values, in wire order.
std::vector<uint8_t> everyFieldPacket(uint8_t groups) {
  std::vector<uint16_t> masks;
  for (unsigned g = 0; g < VN_BIN_GROUP_COUNT; ++g)
    if (groups & (1u << g)) masks.push_back(everyFieldMask(g));
  VnPacketBuilder p(groups, masks);
  for (unsigned g = 0; g < VN_BIN_GROUP_COUNT; ++g) {
    if (!(groups & (1u << g))) continue;
    for (unsigned b = 0; b < kLayout[g].size(); ++b) {
      unsigned i = 0;  // element index across the field's parts
      for (const Part& part : kLayout[g][b]) {
        for (unsigned k = 0; k < part.count; ++k, ++i) {
          switch (part.kind) {
            case 'Q':
              p.u64(u64v(g, b, i));
              break;
            case 'I':
              p.u32(u32v(g, b, i));
              break;
            case 'H':
              p.u16(u16v(g, b, i));
              break;
            case 'B':
              p.u8(u8v(g, b, i));
              break;
            case 'f':
              p.f32(f32v(g, b, i));
              break;
            default:
              p.f64(f64v(g, b, i));
              break;
          }
        }
      }
    }
  }
  return p.finish();
}

void fillFloats(float* dst, unsigned n, unsigned g, unsigned b) {
  for (unsigned i = 0; i < n; ++i) dst[i] = f32v(g, b, i);
}

// What each group's fields write, per the manual's meaning of each member; every other field of
// the group is one the driver does not use and must leave VnBinaryData as it was.
void commonFieldsInto(VnBinaryData& w) {
  w.time_startup_ns = u64v(0, 0, 0);
  w.time_gps_ns = u64v(0, 1, 0);
  fillFloats(w.ypr_deg, 3, 0, 3);
  fillFloats(w.quat_xyzw, 4, 0, 4);
  fillFloats(w.angular_rate_radps, 3, 0, 5);
  w.lat_deg = f64v(0, 6, 0);
  w.lon_deg = f64v(0, 6, 1);
  w.alt_m = f64v(0, 6, 2);
  fillFloats(w.vel_ned_mps, 3, 0, 7);
  fillFloats(w.accel_mps2, 3, 0, 8);
  fillFloats(w.mag_gauss, 3, 0, 10);  // MagPres: mag[3], then temperature and pressure
  w.temp_c = f32v(0, 10, 3);
  w.pressure_kpa = f32v(0, 10, 4);
  w.ins_status = u16v(0, 12, 0);
  w.has |= VN_HAS_TIME_STARTUP | VN_HAS_TIME_GPS | VN_HAS_YPR | VN_HAS_QUATERNION |
           VN_HAS_ANGULAR_RATE | VN_HAS_POSITION_LLA | VN_HAS_VEL_NED | VN_HAS_ACCEL | VN_HAS_MAG |
           VN_HAS_TEMP | VN_HAS_PRESSURE | VN_HAS_INS_STATUS;
}

void timeFieldsInto(VnBinaryData& w) {
  w.time_startup_ns = u64v(1, 0, 0);
  w.time_gps_ns = u64v(1, 1, 0);
  w.gps_tow_ns = u64v(1, 2, 0);
  w.gps_week = u16v(1, 3, 0);
  w.has |= VN_HAS_TIME_STARTUP | VN_HAS_TIME_GPS | VN_HAS_GPS_TOW | VN_HAS_GPS_WEEK;
}

void imuFieldsInto(VnBinaryData& w) {
  w.temp_c = f32v(2, 4, 0);
  w.pressure_kpa = f32v(2, 5, 0);
  fillFloats(w.mag_gauss, 3, 2, 8);
  fillFloats(w.accel_mps2, 3, 2, 9);
  fillFloats(w.angular_rate_radps, 3, 2, 10);
  w.has |= VN_HAS_TEMP | VN_HAS_PRESSURE | VN_HAS_MAG | VN_HAS_ACCEL | VN_HAS_ANGULAR_RATE;
}

void gpsFieldsInto(VnBinaryData& w) {
  w.gps_tow_ns = u64v(3, 1, 0);
  w.gps_week = u16v(3, 2, 0);
  w.num_sats = u8v(3, 3, 0);
  w.gps_fix = u8v(3, 4, 0);
  w.gps_lat_deg = f64v(3, 5, 0);
  w.gps_lon_deg = f64v(3, 5, 1);
  w.gps_alt_m = f64v(3, 5, 2);
  fillFloats(w.gps_vel_ned_mps, 3, 3, 7);
  fillFloats(w.gps_pos_unc_ned_m, 3, 3, 9);
  w.gps_vel_unc_mps = f32v(3, 10, 0);
  w.has |= VN_HAS_GPS_TOW | VN_HAS_GPS_WEEK | VN_HAS_NUM_SATS | VN_HAS_GPS_FIX | VN_HAS_GPS_LLA |
           VN_HAS_GPS_VEL_NED | VN_HAS_GPS_POS_UNC | VN_HAS_GPS_VEL_UNC;
}

void attitudeFieldsInto(VnBinaryData& w) {
  fillFloats(w.ypr_deg, 3, 4, 1);
  fillFloats(w.quat_xyzw, 4, 4, 2);
  fillFloats(w.ypr_unc_deg, 3, 4, 8);
  w.has |= VN_HAS_YPR | VN_HAS_QUATERNION | VN_HAS_YPR_UNC;
}

void insFieldsInto(VnBinaryData& w) {
  w.ins_status = u16v(5, 0, 0);
  w.lat_deg = f64v(5, 1, 0);
  w.lon_deg = f64v(5, 1, 1);
  w.alt_m = f64v(5, 1, 2);
  fillFloats(w.vel_ned_mps, 3, 5, 4);
  w.ins_pos_unc_m = f32v(5, 9, 0);
  w.ins_vel_unc_mps = f32v(5, 10, 0);
  w.has |= VN_HAS_INS_STATUS | VN_HAS_POSITION_LLA | VN_HAS_VEL_NED | VN_HAS_INS_POS_UNC |
           VN_HAS_INS_VEL_UNC;
}

void (*const kFieldsInto[VN_BIN_GROUP_COUNT])(VnBinaryData&) = {commonFieldsInto,   timeFieldsInto,
                                                                imuFieldsInto,      gpsFieldsInto,
                                                                attitudeFieldsInto, insFieldsInto};

// What the decoder must produce for every field of `groups`: the groups in wire order, so a
// later group's field replaces an earlier group's value of the same quantity.
VnBinaryData expectedFor(uint8_t groups) {
  VnBinaryData w;
  std::memset(&w, 0, sizeof w);  // padding included, as the decoder clears it
  w.groups = groups;
  for (unsigned g = 0; g < VN_BIN_GROUP_COUNT; ++g) {
    if (!(groups & (1u << g))) continue;
    w.masks[g] = everyFieldMask(g);
    kFieldsInto[g](w);
  }
  return w;
}

std::string hex(const void* p, size_t n) {
  std::string s;
  char byte[4];
  for (size_t i = 0; i < n; ++i) {
    std::snprintf(byte, sizeof byte, "%02x", static_cast<const uint8_t*>(p)[i]);
    s += byte;
  }
  return s;
}

// Bit for bit, member by member (so a failure names the member), then the whole struct.
#define EXPECT_SAME_BITS(member) \
  EXPECT_EQ(hex(&want.member, sizeof want.member), hex(&got.member, sizeof got.member)) << #member
void expectSameBits(const VnBinaryData& want, const VnBinaryData& got) {
  EXPECT_SAME_BITS(has);
  EXPECT_SAME_BITS(groups);
  EXPECT_SAME_BITS(masks);
  EXPECT_SAME_BITS(time_startup_ns);
  EXPECT_SAME_BITS(time_gps_ns);
  EXPECT_SAME_BITS(gps_tow_ns);
  EXPECT_SAME_BITS(gps_week);
  EXPECT_SAME_BITS(ypr_deg);
  EXPECT_SAME_BITS(quat_xyzw);
  EXPECT_SAME_BITS(angular_rate_radps);
  EXPECT_SAME_BITS(lat_deg);
  EXPECT_SAME_BITS(lon_deg);
  EXPECT_SAME_BITS(alt_m);
  EXPECT_SAME_BITS(vel_ned_mps);
  EXPECT_SAME_BITS(accel_mps2);
  EXPECT_SAME_BITS(mag_gauss);
  EXPECT_SAME_BITS(temp_c);
  EXPECT_SAME_BITS(pressure_kpa);
  EXPECT_SAME_BITS(ins_status);
  EXPECT_SAME_BITS(num_sats);
  EXPECT_SAME_BITS(gps_fix);
  EXPECT_SAME_BITS(gps_lat_deg);
  EXPECT_SAME_BITS(gps_lon_deg);
  EXPECT_SAME_BITS(gps_alt_m);
  EXPECT_SAME_BITS(gps_vel_ned_mps);
  EXPECT_SAME_BITS(ypr_unc_deg);
  EXPECT_SAME_BITS(ins_pos_unc_m);
  EXPECT_SAME_BITS(ins_vel_unc_mps);
  EXPECT_SAME_BITS(gps_pos_unc_ned_m);
  EXPECT_SAME_BITS(gps_vel_unc_mps);
  // A member added to VnBinaryData but not to the list above still has to match here.
  EXPECT_EQ(hex(&want, sizeof want), hex(&got, sizeof got)) << "whole VnBinaryData";
}
#undef EXPECT_SAME_BITS

TEST(VnBinaryFields, TheDecoderKnowsTheSizeTheManualGivesEveryFieldAndNoOther) {
  for (unsigned g = 0; g < VN_BIN_GROUP_COUNT; ++g) {
    for (unsigned b = 0; b < 16; ++b) {
      size_t bytes = 0;
      if (b < kLayout[g].size())
        for (const Part& part : kLayout[g][b]) bytes += partBytes(part);
      EXPECT_EQ(bytes, vn_bin_field_size(g, b)) << "group " << g << " bit " << b;
    }
  }
}

TEST(VnBinaryFields, EachGroupAloneWithEveryFieldSetPutsEachFieldInItsMember) {
  for (unsigned g = 0; g < VN_BIN_GROUP_COUNT; ++g) {
    SCOPED_TRACE("group " + std::to_string(g));
    const uint8_t groups = static_cast<uint8_t>(1u << g);
    const std::vector<uint8_t> p = everyFieldPacket(groups);
    VnBinaryData got;
    ASSERT_EQ(VN_BIN_OK, vn_bin_decode(p.data(), p.size(), &got));
    expectSameBits(expectedFor(groups), got);
  }
}

TEST(VnBinaryFields, InThePacketWithEveryFieldTheLaterGroupWinsAQuantityTwoGroupsCarry) {
  // Common's attitude, rates, position and times are replaced by the Time, IMU, Attitude and
  // INS groups' own fields, and the Time group's GPS time by the GPS group's.
  const std::vector<uint8_t> p = everyFieldPacket(static_cast<uint8_t>(VN_GROUPS_VALID));
  ASSERT_EQ(static_cast<size_t>(VN_BIN_MAX_PACKET), p.size());
  VnBinaryData got;
  ASSERT_EQ(VN_BIN_OK, vn_bin_decode(p.data(), p.size(), &got));
  expectSameBits(expectedFor(static_cast<uint8_t>(VN_GROUPS_VALID)), got);
  EXPECT_EQ(f32v(4, 1, 0), got.ypr_deg[0]);       // Attitude YPR, not Common's
  EXPECT_EQ(f64v(5, 1, 0), got.lat_deg);          // INS PosLla, not Common's
  EXPECT_EQ(u64v(3, 1, 0), got.gps_tow_ns);       // GPS Tow, not Time's
  EXPECT_EQ(u64v(1, 0, 0), got.time_startup_ns);  // Time's, not Common's
}

}  // namespace
