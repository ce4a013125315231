#include "vn_encode.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

#include "vn_binary.h"
#include "vn_checksum.h"

#define NS_PER_WEEK 604800000000000ull
/* Python's math.radians multiplies by this one constant: the same product, bit for bit. */
#define DEG_TO_RAD (3.14159265358979323846 / 180.0)

typedef struct {
  uint8_t *out;
  size_t cap;
  size_t len;
  int ok;
} Writer;

static void put_u8(Writer *w, uint8_t v) {
  if (w->len >= w->cap) {
    w->ok = 0;
    return;
  }
  w->out[w->len++] = v;
}

static void put_le(Writer *w, uint64_t v, unsigned bytes) {
  unsigned i;
  for (i = 0u; i < bytes; ++i) {
    put_u8(w, (uint8_t)(v >> (8u * i)));
  }
}

static void put_f64(Writer *w, double x) {
  uint64_t u;
  memcpy(&u, &x, sizeof u);
  put_le(w, u, 8u);
}

/* Rounded as Python's struct.pack('<f') rounds (a C cast), which refuses a finite value that
 * only fits as infinity: so does this. */
static void put_f32(Writer *w, double x) {
  const float y = (float)x;
  uint32_t u;
  if (isinf(y) && !isinf(x)) {
    w->ok = 0;
    return;
  }
  memcpy(&u, &y, sizeof u);
  put_le(w, u, 4u);
}

/* vn200_emulation.quat_ned: body relative to NED, (x, y, z, w), the same operations in the same
 * order (Python's math.cos and math.sin are the C library's). */
static void put_quaternion(Writer *w, const double ypr_deg[3]) {
  const double yaw = ypr_deg[0] * DEG_TO_RAD, pitch = ypr_deg[1] * DEG_TO_RAD,
               roll = ypr_deg[2] * DEG_TO_RAD;
  double q[4], cy, sy, cp, sp, cr, sr;
  if (isinf(yaw) || isinf(pitch) || isinf(roll)) {
    w->ok = 0; /* math.cos(inf) raises */
    return;
  }
  cy = cos(yaw / 2);
  sy = sin(yaw / 2);
  cp = cos(pitch / 2);
  sp = sin(pitch / 2);
  cr = cos(roll / 2);
  sr = sin(roll / 2);
  q[0] = sr * cp * cy - cr * sp * sy;
  q[1] = cr * sp * cy + sr * cp * sy;
  q[2] = cr * cp * sy - sr * sp * cy;
  q[3] = cr * cp * cy + sr * sp * sy;
  put_f32(w, q[0]);
  put_f32(w, q[1]);
  put_f32(w, q[2]);
  put_f32(w, q[3]);
}

typedef enum {
  ENC_U8,
  ENC_U16,
  ENC_U64,
  ENC_F32,
  ENC_F64,
  ENC_QUAT,
  ENC_GPS_TOW,
  ENC_GPS_WEEK
} EncKind;

/* A field the solution carries: `count` values of `kind` from the solution's member at `offset`. */
typedef struct {
  uint8_t group;
  uint8_t bit;
  uint8_t kind;
  uint8_t count;
  size_t offset;
} EncField;

#define ENC_FIELD(g, b, kind, n, member) \
  { g, b, kind, n, offsetof(VnSolution, member) }

/* vn200_emulation.field_bytes, in the manual's field order; MagPres is the three magnetic
 * components, temperature and pressure: five doubles in a row in VnSolution. */
static const EncField k_fields[] = {
    ENC_FIELD(0u, 0u, ENC_U64, 1u, time_startup_ns),
    ENC_FIELD(0u, 1u, ENC_U64, 1u, time_gps_ns),
    ENC_FIELD(0u, 3u, ENC_F32, 3u, ypr_deg),
    ENC_FIELD(0u, 4u, ENC_QUAT, 3u, ypr_deg),
    ENC_FIELD(0u, 5u, ENC_F32, 3u, angular_rate_radps),
    ENC_FIELD(0u, 6u, ENC_F64, 3u, lla),
    ENC_FIELD(0u, 7u, ENC_F32, 3u, vel_ned_mps),
    ENC_FIELD(0u, 8u, ENC_F32, 3u, accel_mps2),
    ENC_FIELD(0u, 10u, ENC_F32, 5u, mag_gauss),
    ENC_FIELD(0u, 12u, ENC_U16, 1u, ins_status),
    ENC_FIELD(1u, 0u, ENC_U64, 1u, time_startup_ns),
    ENC_FIELD(1u, 2u, ENC_GPS_TOW, 1u, time_gps_ns),
    ENC_FIELD(1u, 3u, ENC_GPS_WEEK, 1u, time_gps_ns),
    ENC_FIELD(3u, 3u, ENC_U8, 1u, num_sats),
    ENC_FIELD(3u, 4u, ENC_U8, 1u, gps_fix),
    ENC_FIELD(3u, 9u, ENC_F32, 3u, gps_pos_unc_m),
    ENC_FIELD(3u, 10u, ENC_F32, 1u, gps_vel_unc_mps),
    ENC_FIELD(4u, 8u, ENC_F32, 3u, ypr_unc_deg),
    ENC_FIELD(5u, 0u, ENC_U16, 1u, ins_status),
    ENC_FIELD(5u, 1u, ENC_F64, 3u, lla),
    ENC_FIELD(5u, 4u, ENC_F32, 3u, vel_ned_mps),
    ENC_FIELD(5u, 9u, ENC_F32, 1u, ins_pos_unc_m),
    ENC_FIELD(5u, 10u, ENC_F32, 1u, ins_vel_unc_mps),
};

/* MagPres reads five doubles from mag_gauss on: they must lie in a row. */
typedef char mag_pres_in_a_row[(offsetof(VnSolution, pressure_kpa) ==
                                offsetof(VnSolution, mag_gauss) + 4u * sizeof(double))
                                   ? 1
                                   : -1];

/* Writes field `bit` of group index `g`; returns 0 if the solution does not carry it. */
static int put_field(Writer *w, unsigned g, unsigned bit, const VnSolution *s) {
  size_t i;
  for (i = 0u; i < sizeof k_fields / sizeof k_fields[0]; ++i) {
    const EncField *f = &k_fields[i];
    const unsigned char *p = (const unsigned char *)s + f->offset;
    double d[5];
    uint64_t u = 0u;
    uint16_t h;
    unsigned k;
    if (f->group != g || f->bit != bit) {
      continue;
    }
    switch (f->kind) {
      case ENC_U8:
        put_u8(w, *p);
        break;
      case ENC_U16:
        memcpy(&h, p, sizeof h);
        put_le(w, h, 2u);
        break;
      case ENC_F32:
      case ENC_F64:
      case ENC_QUAT:
        memcpy(d, p, f->count * sizeof d[0]);
        for (k = 0u; f->kind != ENC_QUAT && k < f->count; ++k) {
          if (f->kind == ENC_F32) {
            put_f32(w, d[k]);
          } else {
            put_f64(w, d[k]);
          }
        }
        if (f->kind == ENC_QUAT) {
          put_quaternion(w, d);
        }
        break;
      default: /* the 64-bit times */
        memcpy(&u, p, sizeof u);
        /* 2^64 ns are 30,500 weeks: the week always fits its 16 bits. */
        put_le(w,
               f->kind == ENC_GPS_TOW    ? u % NS_PER_WEEK
               : f->kind == ENC_GPS_WEEK ? u / NS_PER_WEEK
                                         : u,
               f->kind == ENC_GPS_WEEK ? 2u : 8u);
        break;
    }
    return 1;
  }
  return 0;
}

size_t vn_encode_solution_size(void) { return sizeof(VnSolution); }

size_t vn_bin_encode(uint8_t groups, const uint16_t *masks, const VnSolution *s, uint8_t *out,
                     size_t cap) {
  Writer w;
  unsigned g;
  uint16_t crc;
  if (masks == NULL || s == NULL || out == NULL) {
    return 0u;
  }
  w.out = out;
  w.cap = cap;
  w.len = 0u;
  w.ok = 1;
  put_u8(&w, VN_BIN_SYNC);
  put_u8(&w, groups);
  for (g = 0u; g < VN_BIN_GROUP_COUNT; ++g) {
    if ((groups & (1u << g)) != 0u) {
      put_le(&w, masks[g], 2u);
    }
  }
  for (g = 0u; g < VN_BIN_GROUP_COUNT; ++g) {
    unsigned b;
    if ((groups & (1u << g)) == 0u) {
      continue;
    }
    for (b = 0u; b < 16u; ++b) {
      if ((masks[g] & (1u << b)) != 0u && !put_field(&w, g, b, s)) {
        unsigned i;
        for (i = 0u; i < vn_bin_field_size(g, b); ++i) {
          put_u8(&w, 0u);
        }
      }
    }
  }
  if (!w.ok) {
    return 0u;
  }
  crc = vn_crc16(out + 1, w.len - 1u);
  put_u8(&w, (uint8_t)(crc >> 8));
  put_u8(&w, (uint8_t)crc);
  return w.ok ? w.len : 0u;
}
