#include "vn_binary.h"

#include <string.h>

#include "vn_checksum.h"

/* How a field's bytes are stored: elements of one type, little endian on the wire. */
enum { VN_KIND_SKIP = 0, VN_KIND_U8, VN_KIND_U16, VN_KIND_U64, VN_KIND_F32, VN_KIND_F64 };

/* One (group, bit) field: its size on the wire and, for a field the driver keeps, where it goes.
 * A kept field is stored whole, size / element size elements from `offset` on, and sets `has`. */
typedef struct {
  uint8_t size; /* bytes; 0 = reserved / not defined for the VN-200, so the packet is refused */
  uint8_t kind;
  uint16_t offset; /* offsetof(VnBinaryData, first member written) */
  uint32_t has;
} VnFieldSpec;

#define SKIP(size) \
  { (size), VN_KIND_SKIP, 0u, 0u }
#define KEEP(size, kind, member, has) \
  { (size), (kind), (uint16_t)offsetof(VnBinaryData, member), (has) }

/* The fields, per group, per mask bit: VN-200 User Manual, binary group tables (Common, Time,
 * IMU, GPS, Attitude, INS). Bits not listed are reserved. Where two groups carry the same
 * quantity, the later group's field is decoded last and wins. */
static const VnFieldSpec k_fields[VN_BIN_GROUP_COUNT][16] = {
    {
        /* Common */
        KEEP(8, VN_KIND_U64, time_startup_ns, VN_HAS_TIME_STARTUP),     /* TimeStartup */
        KEEP(8, VN_KIND_U64, time_gps_ns, VN_HAS_TIME_GPS),             /* TimeGps */
        SKIP(8),                                                        /* TimeSyncIn */
        KEEP(12, VN_KIND_F32, ypr_deg, VN_HAS_YPR),                     /* YawPitchRoll */
        KEEP(16, VN_KIND_F32, quat_xyzw, VN_HAS_QUATERNION),            /* Quaternion */
        KEEP(12, VN_KIND_F32, angular_rate_radps, VN_HAS_ANGULAR_RATE), /* AngularRate */
        KEEP(24, VN_KIND_F64, lat_deg, VN_HAS_POSITION_LLA), /* Position: lat, lon, alt */
        KEEP(12, VN_KIND_F32, vel_ned_mps, VN_HAS_VEL_NED),  /* Velocity (NED) */
        KEEP(12, VN_KIND_F32, accel_mps2, VN_HAS_ACCEL),     /* Accel */
        SKIP(24),                                            /* Imu (uncompensated) */
        KEEP(20, VN_KIND_F32, mag_gauss, VN_HAS_MAG | VN_HAS_TEMP | VN_HAS_PRESSURE), /* MagPres */
        SKIP(28),                                            /* DeltaTheta */
        KEEP(2, VN_KIND_U16, ins_status, VN_HAS_INS_STATUS), /* InsStatus */
        SKIP(4),                                             /* SyncInCnt */
        SKIP(8),                                             /* TimeGpsPps */
    },
    {
        /* Time */
        KEEP(8, VN_KIND_U64, time_startup_ns, VN_HAS_TIME_STARTUP), /* TimeStartup */
        KEEP(8, VN_KIND_U64, time_gps_ns, VN_HAS_TIME_GPS),         /* TimeGps */
        KEEP(8, VN_KIND_U64, gps_tow_ns, VN_HAS_GPS_TOW),           /* GpsTow */
        KEEP(2, VN_KIND_U16, gps_week, VN_HAS_GPS_WEEK),            /* GpsWeek */
        SKIP(8),                                                    /* TimeSyncIn */
        SKIP(8),                                                    /* TimeGpsPps */
        SKIP(8),                                                    /* TimeUTC */
        SKIP(4),                                                    /* SyncInCnt */
        SKIP(4),                                                    /* SyncOutCnt */
        SKIP(1),                                                    /* TimeStatus */
    },
    {
        /* IMU (compensated values kept) */
        SKIP(2),                                                        /* ImuStatus */
        SKIP(12),                                                       /* UncompMag */
        SKIP(12),                                                       /* UncompAccel */
        SKIP(12),                                                       /* UncompGyro */
        KEEP(4, VN_KIND_F32, temp_c, VN_HAS_TEMP),                      /* Temp */
        KEEP(4, VN_KIND_F32, pressure_kpa, VN_HAS_PRESSURE),            /* Pres */
        SKIP(16),                                                       /* DeltaTheta */
        SKIP(12),                                                       /* DeltaVel */
        KEEP(12, VN_KIND_F32, mag_gauss, VN_HAS_MAG),                   /* Mag */
        KEEP(12, VN_KIND_F32, accel_mps2, VN_HAS_ACCEL),                /* Accel */
        KEEP(12, VN_KIND_F32, angular_rate_radps, VN_HAS_ANGULAR_RATE), /* AngularRate */
    },
    {
        /* GPS */
        SKIP(8),                                                      /* UTC */
        KEEP(8, VN_KIND_U64, gps_tow_ns, VN_HAS_GPS_TOW),             /* Tow */
        KEEP(2, VN_KIND_U16, gps_week, VN_HAS_GPS_WEEK),              /* Week */
        KEEP(1, VN_KIND_U8, num_sats, VN_HAS_NUM_SATS),               /* NumSats */
        KEEP(1, VN_KIND_U8, gps_fix, VN_HAS_GPS_FIX),                 /* Fix */
        KEEP(24, VN_KIND_F64, gps_lat_deg, VN_HAS_GPS_LLA),           /* PosLla: lat, lon, alt */
        SKIP(24),                                                     /* PosEcef */
        KEEP(12, VN_KIND_F32, gps_vel_ned_mps, VN_HAS_GPS_VEL_NED),   /* VelNed */
        SKIP(12),                                                     /* VelEcef */
        KEEP(12, VN_KIND_F32, gps_pos_unc_ned_m, VN_HAS_GPS_POS_UNC), /* PosU */
        KEEP(4, VN_KIND_F32, gps_vel_unc_mps, VN_HAS_GPS_VEL_UNC),    /* VelU */
        SKIP(4),                                                      /* TimeU */
    },
    {
        /* Attitude */
        SKIP(2),                                             /* VpeStatus */
        KEEP(12, VN_KIND_F32, ypr_deg, VN_HAS_YPR),          /* YawPitchRoll */
        KEEP(16, VN_KIND_F32, quat_xyzw, VN_HAS_QUATERNION), /* Quaternion */
        SKIP(36),                                            /* DCM */
        SKIP(12),                                            /* MagNed */
        SKIP(12),                                            /* AccelNed */
        SKIP(12),                                            /* LinearAccelBody */
        SKIP(12),                                            /* LinearAccelNed */
        KEEP(12, VN_KIND_F32, ypr_unc_deg, VN_HAS_YPR_UNC),  /* YprU */
    },
    {
        /* INS */
        KEEP(2, VN_KIND_U16, ins_status, VN_HAS_INS_STATUS),       /* InsStatus */
        KEEP(24, VN_KIND_F64, lat_deg, VN_HAS_POSITION_LLA),       /* PosLla: lat, lon, alt */
        SKIP(24),                                                  /* PosEcef */
        SKIP(12),                                                  /* VelBody */
        KEEP(12, VN_KIND_F32, vel_ned_mps, VN_HAS_VEL_NED),        /* VelNed */
        SKIP(12),                                                  /* VelEcef */
        SKIP(12),                                                  /* MagEcef */
        SKIP(12),                                                  /* AccelEcef */
        SKIP(12),                                                  /* LinearAccelEcef */
        KEEP(4, VN_KIND_F32, ins_pos_unc_m, VN_HAS_INS_POS_UNC),   /* PosU */
        KEEP(4, VN_KIND_F32, ins_vel_unc_mps, VN_HAS_INS_VEL_UNC), /* VelU */
    },
};

/* A field stored across several members needs them back to back. C99 has no static_assert: a
 * negative array size stops the build. */
#define VN_FOLLOWS(a, b, gap) (offsetof(VnBinaryData, b) == offsetof(VnBinaryData, a) + (gap))
#define VN_BUILD_CHECK(name, cond) typedef char name[(cond) ? 1 : -1]
VN_BUILD_CHECK(vn_lla_back_to_back,
               VN_FOLLOWS(lat_deg, lon_deg, 8u) && VN_FOLLOWS(lon_deg, alt_m, 8u));
VN_BUILD_CHECK(vn_gps_lla_back_to_back,
               VN_FOLLOWS(gps_lat_deg, gps_lon_deg, 8u) && VN_FOLLOWS(gps_lon_deg, gps_alt_m, 8u));
VN_BUILD_CHECK(vn_mag_pres_back_to_back,
               VN_FOLLOWS(mag_gauss, temp_c, 12u) && VN_FOLLOWS(temp_c, pressure_kpa, 4u));

uint8_t vn_bin_field_size(unsigned group, unsigned bit) {
  if (group >= VN_BIN_GROUP_COUNT || bit >= 16u) {
    return 0u;
  }
  return k_fields[group][bit].size;
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
        uint8_t sz = k_fields[g][b].size;
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
      if (k_fields[g][b].size != 0u) {
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

/* Stores field `f` from the packet bytes at `p` into `d`, one element at a time through
 * memcpy: a char offset into the struct, so no pointer steps past the end of a member array
 * (MagPres and the positions span several members) and no member is read through another type. */
static void store_field(const VnFieldSpec *f, const uint8_t *p, VnBinaryData *d) {
  unsigned char *dst = (unsigned char *)d + f->offset;
  unsigned i;
  switch (f->kind) {
    case VN_KIND_U8:
      memcpy(dst, p, f->size);
      break;
    case VN_KIND_U16:
      for (i = 0u; i < f->size; i += 2u) {
        uint16_t v = rd_u16(p + i);
        memcpy(dst + i, &v, sizeof v);
      }
      break;
    case VN_KIND_U64:
      for (i = 0u; i < f->size; i += 8u) {
        uint64_t v = rd_u64(p + i);
        memcpy(dst + i, &v, sizeof v);
      }
      break;
    case VN_KIND_F32:
      for (i = 0u; i < f->size; i += 4u) {
        float v = rd_f32(p + i);
        memcpy(dst + i, &v, sizeof v);
      }
      break;
    case VN_KIND_F64:
      for (i = 0u; i < f->size; i += 8u) {
        double v = rd_f64(p + i);
        memcpy(dst + i, &v, sizeof v);
      }
      break;
    default: /* a field the driver does not use: skipped by its size */
      return;
  }
  d->has |= f->has;
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
        store_field(&k_fields[g][b], pkt + pos, out);
        pos += k_fields[g][b].size;
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
