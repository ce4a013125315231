/* VN-200 binary output packets: layout, field sizes and a decoder into a plain struct.
 * VN-200 User Manual, "Binary Output Messages" chapter (sections Binary Group 1 Common ... Binary
 * Group 6 INS): a packet is
 *   0xFA | groups (1 byte, bit n = group n+1) | one 16-bit little-endian field mask per group
 *   present, in group order | fields, group by group, each in mask bit order, little endian |
 *   CRC-16 big-endian over everything after the sync.
 * Bit 15 of a field mask would announce an extension word; the VN-200 never sets it and we reject
 * it, as we reject any bit the manual leaves reserved: without a known size the packet length is
 * unknowable, so such a packet is dropped and counted. */
#ifndef VN_BINARY_H
#define VN_BINARY_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define VN_BIN_SYNC 0xFAu
#define VN_BIN_GROUP_COUNT 6u
/* Groups byte bits (manual, "Binary Output Register" group selection). */
#define VN_GROUP_COMMON 0x01u
#define VN_GROUP_TIME 0x02u
#define VN_GROUP_IMU 0x04u
#define VN_GROUP_GPS 0x08u
#define VN_GROUP_ATTITUDE 0x10u
#define VN_GROUP_INS 0x20u
#define VN_GROUPS_VALID 0x3Fu

/* Common group (group 1) field bits. */
#define VN_COMMON_TIME_STARTUP 0x0001u
#define VN_COMMON_TIME_GPS 0x0002u
#define VN_COMMON_TIME_SYNC_IN 0x0004u
#define VN_COMMON_YPR 0x0008u
#define VN_COMMON_QUATERNION 0x0010u
#define VN_COMMON_ANGULAR_RATE 0x0020u
#define VN_COMMON_POSITION 0x0040u
#define VN_COMMON_VELOCITY 0x0080u
#define VN_COMMON_ACCEL 0x0100u
#define VN_COMMON_IMU 0x0200u
#define VN_COMMON_MAG_PRES 0x0400u
#define VN_COMMON_DELTA_THETA 0x0800u
#define VN_COMMON_INS_STATUS 0x1000u
#define VN_COMMON_SYNC_IN_CNT 0x2000u
#define VN_COMMON_TIME_GPS_PPS 0x4000u
/* Time group (group 2). */
#define VN_TIME_TIME_STARTUP 0x0001u
#define VN_TIME_TIME_GPS 0x0002u
#define VN_TIME_GPS_TOW 0x0004u
#define VN_TIME_GPS_WEEK 0x0008u
#define VN_TIME_TIME_UTC 0x0040u
#define VN_TIME_TIME_STATUS 0x0200u
/* IMU group (group 3). */
#define VN_IMU_TEMP 0x0010u
#define VN_IMU_PRES 0x0020u
#define VN_IMU_MAG 0x0100u
#define VN_IMU_ACCEL 0x0200u
#define VN_IMU_ANGULAR_RATE 0x0400u
/* GPS group (group 4). */
#define VN_GPS_UTC 0x0001u
#define VN_GPS_TOW 0x0002u
#define VN_GPS_WEEK 0x0004u
#define VN_GPS_NUM_SATS 0x0008u
#define VN_GPS_FIX 0x0010u
#define VN_GPS_POS_LLA 0x0020u
#define VN_GPS_VEL_NED 0x0080u
#define VN_GPS_POS_U 0x0200u
#define VN_GPS_VEL_U 0x0400u
/* Attitude group (group 5). */
#define VN_ATT_YPR 0x0002u
#define VN_ATT_QUATERNION 0x0004u
#define VN_ATT_MAG_NED 0x0010u
#define VN_ATT_YPR_U 0x0100u
/* INS group (group 6). */
#define VN_INS_STATUS 0x0001u
#define VN_INS_POS_LLA 0x0002u
#define VN_INS_VEL_NED 0x0010u
#define VN_INS_POS_U 0x0200u
#define VN_INS_VEL_U 0x0400u

/* Largest packet the documented fields allow: sync + groups + 6 masks + every field + CRC.
 * vn_bin_max_packet_len() computes it from the table; a test pins the two together. */
#define VN_BIN_MAX_PACKET 751u
#define VN_BIN_MIN_PACKET 6u /* sync, groups, one mask, CRC; a packet with no field is legal */

/* Size in bytes of field `bit` (0-15) of group index `group` (0 = Common ... 5 = INS);
 * 0 if the manual defines no field there. */
uint8_t vn_bin_field_size(unsigned group, unsigned bit);
/* Header+payload+CRC length implied by a groups byte and masks; 0 if any group or field bit is
 * not documented. `masks` holds one entry per set group bit, in group order. */
size_t vn_bin_packet_len(uint8_t groups, const uint16_t *masks, size_t mask_count);
size_t vn_bin_max_packet_len(void);

/* Presence bits of VnBinaryData.has. */
enum {
  VN_HAS_TIME_STARTUP = 1u << 0,
  VN_HAS_TIME_GPS = 1u << 1,
  VN_HAS_GPS_TOW = 1u << 2,
  VN_HAS_GPS_WEEK = 1u << 3,
  VN_HAS_YPR = 1u << 4,
  VN_HAS_QUATERNION = 1u << 5,
  VN_HAS_ANGULAR_RATE = 1u << 6,
  VN_HAS_POSITION_LLA = 1u << 7,
  VN_HAS_VEL_NED = 1u << 8,
  VN_HAS_ACCEL = 1u << 9,
  VN_HAS_MAG = 1u << 10,
  VN_HAS_TEMP = 1u << 11,
  VN_HAS_PRESSURE = 1u << 12,
  VN_HAS_INS_STATUS = 1u << 13,
  VN_HAS_NUM_SATS = 1u << 14,
  VN_HAS_GPS_FIX = 1u << 15,
  VN_HAS_YPR_UNC = 1u << 16,
  VN_HAS_INS_POS_UNC = 1u << 17,
  VN_HAS_INS_VEL_UNC = 1u << 18,
  VN_HAS_GPS_POS_UNC = 1u << 19,
  VN_HAS_GPS_VEL_UNC = 1u << 20,
  VN_HAS_GPS_LLA = 1u << 21,
  VN_HAS_GPS_VEL_NED = 1u << 22
};

/* One decoded binary packet. Frames: attitude and velocity relative to local NED, body rates and
 * accelerations in the sensor's body frame (x forward, y right, z down). */
typedef struct {
  uint32_t has;
  uint8_t groups;
  uint16_t masks[VN_BIN_GROUP_COUNT]; /* indexed by group, 0 when the group is absent */
  uint64_t time_startup_ns;
  uint64_t time_gps_ns; /* since the GPS epoch 1980-01-06 */
  uint64_t gps_tow_ns;  /* GPS time of week */
  uint16_t gps_week;
  float ypr_deg[3];   /* yaw, pitch, roll */
  float quat_xyzw[4]; /* body relative to NED, scalar last as the sensor sends it */
  float angular_rate_radps[3];
  double lat_deg, lon_deg, alt_m; /* INS (or Common) position, WGS84 ellipsoid height */
  float vel_ned_mps[3];
  float accel_mps2[3];
  float mag_gauss[3];
  float temp_c;
  float pressure_kpa;
  uint16_t ins_status;
  uint8_t num_sats;
  uint8_t gps_fix; /* 0 none, 1 time only, 2 2D, 3 3D */
  double gps_lat_deg, gps_lon_deg, gps_alt_m;
  float gps_vel_ned_mps[3];
  float ypr_unc_deg[3];
  float ins_pos_unc_m;
  float ins_vel_unc_mps;
  float gps_pos_unc_ned_m[3];
  float gps_vel_unc_mps;
} VnBinaryData;

typedef enum {
  VN_BIN_OK = 0,
  VN_BIN_ERR_NULL,
  VN_BIN_ERR_SHORT, /* fewer bytes than the header announces */
  VN_BIN_ERR_SYNC,
  VN_BIN_ERR_GROUPS, /* no group or an undocumented group bit */
  VN_BIN_ERR_FIELD,  /* an undocumented field bit */
  VN_BIN_ERR_LENGTH, /* length differs from what the masks imply */
  VN_BIN_ERR_CRC,
  VN_BIN_ERR_NONFINITE /* a decoded float field is NaN or infinite */
} VnBinResult;

/* Decodes one complete packet (sync through CRC). `out` is fully written on every return.
 * Not reentrant (one flag for non-finite fields): call from one thread or task at a time. */
VnBinResult vn_bin_decode(const uint8_t *pkt, size_t len, VnBinaryData *out);

/* INS status word helpers (manual, "INS Status" in the INS group): mode in bits 0-1, GNSS fix in
 * bit 2, error flags in bits 3-6. */
#define VN_INS_STATUS_MODE(s) ((unsigned)((s)&0x3u))
#define VN_INS_STATUS_GNSS_FIX(s) ((unsigned)(((s) >> 2) & 0x1u))

#ifdef __cplusplus
}
#endif
#endif
