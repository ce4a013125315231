#include "vn_binary.h"

#include <string.h>

#include "vn_checksum.h"

/* Field sizes in bytes, per group, per mask bit: VN-200 User Manual, binary group tables
 * (Common, Time, IMU, GPS, Attitude, INS). 0 = reserved / not defined for the VN-200. */
static const uint8_t k_field_size[VN_BIN_GROUP_COUNT][16] = {
    /* Common: TimeStartup, TimeGps, TimeSyncIn, YPR, Quaternion, AngularRate, Position(LLA),
     * Velocity(NED), Accel, Imu, MagPres, DeltaTheta, InsStatus, SyncInCnt, TimeGpsPps */
    {8, 8, 8, 12, 16, 12, 24, 12, 12, 24, 20, 28, 2, 4, 8, 0},
    /* Time: TimeStartup, TimeGps, GpsTow, GpsWeek, TimeSyncIn, TimeGpsPps, TimeUTC, SyncInCnt,
     * SyncOutCnt, TimeStatus */
    {8, 8, 8, 2, 8, 8, 8, 4, 4, 1, 0, 0, 0, 0, 0, 0},
    /* IMU: ImuStatus, UncompMag, UncompAccel, UncompGyro, Temp, Pres, DeltaTheta, DeltaVel, Mag,
     * Accel, AngularRate */
    {2, 12, 12, 12, 4, 4, 16, 12, 12, 12, 12, 0, 0, 0, 0, 0},
    /* GPS: UTC, Tow, Week, NumSats, Fix, PosLla, PosEcef, VelNed, VelEcef, PosU, VelU, TimeU */
    {8, 8, 2, 1, 1, 24, 24, 12, 12, 12, 4, 4, 0, 0, 0, 0},
    /* Attitude: VpeStatus, YPR, Quaternion, DCM, MagNed, AccelNed, LinearAccelBody,
     * LinearAccelNed, YprU */
    {2, 12, 16, 36, 12, 12, 12, 12, 12, 0, 0, 0, 0, 0, 0, 0},
    /* INS: InsStatus, PosLla, PosEcef, VelBody, VelNed, VelEcef, MagEcef, AccelEcef,
     * LinearAccelEcef, PosU, VelU */
    {2, 24, 24, 12, 12, 12, 12, 12, 12, 4, 4, 0, 0, 0, 0, 0},
};

uint8_t vn_bin_field_size(unsigned group, unsigned bit) {
  if (group >= VN_BIN_GROUP_COUNT || bit >= 16u) {
    return 0u;
  }
  return k_field_size[group][bit];
}

size_t vn_bin_packet_len(uint8_t groups, const uint16_t *masks, size_t mask_count) {
  size_t len = 2u; /* sync + groups */
  size_t used = 0u;
  unsigned g;
  if (masks == NULL || groups == 0u || (groups & (uint8_t)~VN_GROUPS_VALID) != 0u) {
    return 0u;
  }
  for (g = 0u; g < VN_BIN_GROUP_COUNT; ++g) {
    unsigned b;
    if ((groups & (1u << g)) == 0u) {
      continue;
    }
    if (used >= mask_count) {
      return 0u;
    }
    len += 2u;
    for (b = 0u; b < 16u; ++b) {
      if ((masks[used] & (1u << b)) != 0u) {
        uint8_t sz = k_field_size[g][b];
        if (sz == 0u) {
          return 0u;
        }
        len += sz;
      }
    }
    ++used;
  }
  return len + 2u; /* CRC */
}

size_t vn_bin_max_packet_len(void) {
  uint16_t masks[VN_BIN_GROUP_COUNT] = {0u, 0u, 0u, 0u, 0u, 0u};
  unsigned g;
  for (g = 0u; g < VN_BIN_GROUP_COUNT; ++g) {
    unsigned b;
    masks[g] = 0u;
    for (b = 0u; b < 16u; ++b) {
      if (k_field_size[g][b] != 0u) {
        masks[g] = (uint16_t)(masks[g] | (1u << b));
      }
    }
  }
  return vn_bin_packet_len((uint8_t)VN_GROUPS_VALID, masks, VN_BIN_GROUP_COUNT);
}

/* Little-endian readers: explicit byte assembly keeps the decoder independent of host
 * endianness and alignment (the Due faults on unaligned double loads). */
static uint16_t rd_u16(const uint8_t *p) {
  return (uint16_t)((uint16_t)p[0] | (uint16_t)((uint16_t)p[1] << 8));
}

static uint32_t rd_u32(const uint8_t *p) {
  return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}

static uint64_t rd_u64(const uint8_t *p) {
  return (uint64_t)rd_u32(p) | ((uint64_t)rd_u32(p + 4) << 32);
}

/* Floats are checked on their bit pattern (exponent all ones = NaN or infinity) before they
 * become floats: a NaN attitude must never reach a controller, and the check needs no float
 * arithmetic. A non-finite field marks the whole packet bad. */
static int g_nonfinite;

static float rd_f32(const uint8_t *p) {
  uint32_t u = rd_u32(p);
  float f;
  if (((u >> 23) & 0xFFu) == 0xFFu) {
    g_nonfinite = 1;
    return 0.0f;
  }
  memcpy(&f, &u, sizeof f);
  return f;
}

static double rd_f64(const uint8_t *p) {
  uint64_t u = rd_u64(p);
  double d;
  if (((u >> 52) & 0x7FFu) == 0x7FFu) {
    g_nonfinite = 1;
    return 0.0;
  }
  memcpy(&d, &u, sizeof d);
  return d;
}

static void rd_f32_n(const uint8_t *p, float *dst, unsigned n) {
  unsigned i;
  for (i = 0u; i < n; ++i) {
    dst[i] = rd_f32(p + 4u * i);
  }
}

/* Stores one field the driver uses; every other documented field is skipped by its size. */
static void store_field(unsigned g, unsigned b, const uint8_t *p, VnBinaryData *d) {
  switch (g) {
    case 0u: /* Common */
      switch (b) {
        case 0u:
          d->time_startup_ns = rd_u64(p);
          d->has |= VN_HAS_TIME_STARTUP;
          break;
        case 1u:
          d->time_gps_ns = rd_u64(p);
          d->has |= VN_HAS_TIME_GPS;
          break;
        case 3u:
          rd_f32_n(p, d->ypr_deg, 3u);
          d->has |= VN_HAS_YPR;
          break;
        case 4u:
          rd_f32_n(p, d->quat_xyzw, 4u);
          d->has |= VN_HAS_QUATERNION;
          break;
        case 5u:
          rd_f32_n(p, d->angular_rate_radps, 3u);
          d->has |= VN_HAS_ANGULAR_RATE;
          break;
        case 6u:
          d->lat_deg = rd_f64(p);
          d->lon_deg = rd_f64(p + 8);
          d->alt_m = rd_f64(p + 16);
          d->has |= VN_HAS_POSITION_LLA;
          break;
        case 7u:
          rd_f32_n(p, d->vel_ned_mps, 3u);
          d->has |= VN_HAS_VEL_NED;
          break;
        case 8u:
          rd_f32_n(p, d->accel_mps2, 3u);
          d->has |= VN_HAS_ACCEL;
          break;
        case 10u: /* MagPres: mag[3] gauss, temperature C, pressure kPa */
          rd_f32_n(p, d->mag_gauss, 3u);
          d->temp_c = rd_f32(p + 12);
          d->pressure_kpa = rd_f32(p + 16);
          d->has |= VN_HAS_MAG | VN_HAS_TEMP | VN_HAS_PRESSURE;
          break;
        case 12u:
          d->ins_status = rd_u16(p);
          d->has |= VN_HAS_INS_STATUS;
          break;
        default:
          break;
      }
      break;
    case 1u: /* Time */
      switch (b) {
        case 0u:
          d->time_startup_ns = rd_u64(p);
          d->has |= VN_HAS_TIME_STARTUP;
          break;
        case 1u:
          d->time_gps_ns = rd_u64(p);
          d->has |= VN_HAS_TIME_GPS;
          break;
        case 2u:
          d->gps_tow_ns = rd_u64(p);
          d->has |= VN_HAS_GPS_TOW;
          break;
        case 3u:
          d->gps_week = rd_u16(p);
          d->has |= VN_HAS_GPS_WEEK;
          break;
        default:
          break;
      }
      break;
    case 2u: /* IMU (compensated values) */
      switch (b) {
        case 4u:
          d->temp_c = rd_f32(p);
          d->has |= VN_HAS_TEMP;
          break;
        case 5u:
          d->pressure_kpa = rd_f32(p);
          d->has |= VN_HAS_PRESSURE;
          break;
        case 8u:
          rd_f32_n(p, d->mag_gauss, 3u);
          d->has |= VN_HAS_MAG;
          break;
        case 9u:
          rd_f32_n(p, d->accel_mps2, 3u);
          d->has |= VN_HAS_ACCEL;
          break;
        case 10u:
          rd_f32_n(p, d->angular_rate_radps, 3u);
          d->has |= VN_HAS_ANGULAR_RATE;
          break;
        default:
          break;
      }
      break;
    case 3u: /* GPS */
      switch (b) {
        case 1u:
          d->gps_tow_ns = rd_u64(p);
          d->has |= VN_HAS_GPS_TOW;
          break;
        case 2u:
          d->gps_week = rd_u16(p);
          d->has |= VN_HAS_GPS_WEEK;
          break;
        case 3u:
          d->num_sats = p[0];
          d->has |= VN_HAS_NUM_SATS;
          break;
        case 4u:
          d->gps_fix = p[0];
          d->has |= VN_HAS_GPS_FIX;
          break;
        case 5u:
          d->gps_lat_deg = rd_f64(p);
          d->gps_lon_deg = rd_f64(p + 8);
          d->gps_alt_m = rd_f64(p + 16);
          d->has |= VN_HAS_GPS_LLA;
          break;
        case 7u:
          rd_f32_n(p, d->gps_vel_ned_mps, 3u);
          d->has |= VN_HAS_GPS_VEL_NED;
          break;
        case 9u:
          rd_f32_n(p, d->gps_pos_unc_ned_m, 3u);
          d->has |= VN_HAS_GPS_POS_UNC;
          break;
        case 10u:
          d->gps_vel_unc_mps = rd_f32(p);
          d->has |= VN_HAS_GPS_VEL_UNC;
          break;
        default:
          break;
      }
      break;
    case 4u: /* Attitude */
      switch (b) {
        case 1u:
          rd_f32_n(p, d->ypr_deg, 3u);
          d->has |= VN_HAS_YPR;
          break;
        case 2u:
          rd_f32_n(p, d->quat_xyzw, 4u);
          d->has |= VN_HAS_QUATERNION;
          break;
        case 8u:
          rd_f32_n(p, d->ypr_unc_deg, 3u);
          d->has |= VN_HAS_YPR_UNC;
          break;
        default:
          break;
      }
      break;
    case 5u: /* INS */
      switch (b) {
        case 0u:
          d->ins_status = rd_u16(p);
          d->has |= VN_HAS_INS_STATUS;
          break;
        case 1u:
          d->lat_deg = rd_f64(p);
          d->lon_deg = rd_f64(p + 8);
          d->alt_m = rd_f64(p + 16);
          d->has |= VN_HAS_POSITION_LLA;
          break;
        case 4u:
          rd_f32_n(p, d->vel_ned_mps, 3u);
          d->has |= VN_HAS_VEL_NED;
          break;
        case 9u:
          d->ins_pos_unc_m = rd_f32(p);
          d->has |= VN_HAS_INS_POS_UNC;
          break;
        case 10u:
          d->ins_vel_unc_mps = rd_f32(p);
          d->has |= VN_HAS_INS_VEL_UNC;
          break;
        default:
          break;
      }
      break;
    default:
      break;
  }
}

VnBinResult vn_bin_decode(const uint8_t *pkt, size_t len, VnBinaryData *out) {
  uint16_t masks[VN_BIN_GROUP_COUNT] = {0u, 0u, 0u, 0u, 0u, 0u};
  size_t mask_count = 0u;
  size_t pos;
  size_t expected;
  unsigned g;
  if (out == NULL) {
    return VN_BIN_ERR_NULL;
  }
  memset(out, 0, sizeof *out);
  if (pkt == NULL) {
    return VN_BIN_ERR_NULL;
  }
  if (len < VN_BIN_MIN_PACKET) {
    return VN_BIN_ERR_SHORT;
  }
  if (pkt[0] != VN_BIN_SYNC) {
    return VN_BIN_ERR_SYNC;
  }
  if (pkt[1] == 0u || (pkt[1] & (uint8_t)~VN_GROUPS_VALID) != 0u) {
    return VN_BIN_ERR_GROUPS;
  }
  pos = 2u;
  for (g = 0u; g < VN_BIN_GROUP_COUNT; ++g) {
    if ((pkt[1] & (1u << g)) != 0u) {
      if (pos + 2u > len) {
        return VN_BIN_ERR_SHORT;
      }
      masks[mask_count] = rd_u16(pkt + pos);
      ++mask_count;
      pos += 2u;
    }
  }
  expected = vn_bin_packet_len(pkt[1], masks, mask_count);
  if (expected == 0u) {
    return VN_BIN_ERR_FIELD;
  }
  if (expected != len) {
    return len < expected ? VN_BIN_ERR_SHORT : VN_BIN_ERR_LENGTH;
  }
  if (vn_crc16(pkt + 1, len - 1u) != 0u) {
    return VN_BIN_ERR_CRC;
  }
  g_nonfinite = 0;
  out->groups = pkt[1];
  mask_count = 0u;
  for (g = 0u; g < VN_BIN_GROUP_COUNT; ++g) {
    unsigned b;
    if ((pkt[1] & (1u << g)) == 0u) {
      continue;
    }
    out->masks[g] = masks[mask_count];
    for (b = 0u; b < 16u; ++b) {
      if ((masks[mask_count] & (1u << b)) != 0u) {
        /* pos + size <= len - 2 holds: the total was checked against the table above. */
        store_field(g, b, pkt + pos, out);
        pos += k_field_size[g][b];
      }
    }
    ++mask_count;
  }
  if (g_nonfinite) {
    memset(out, 0, sizeof *out);
    return VN_BIN_ERR_NONFINITE;
  }
  return VN_BIN_OK;
}
