#include "vn_encode.h"

#include <math.h>
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

static void put_f32s(Writer *w, const double *x, unsigned n) {
  unsigned i;
  for (i = 0u; i < n; ++i) {
    put_f32(w, x[i]);
  }
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
  put_f32s(w, q, 4u);
}

/* Writes field `bit` of group index `g`; returns 0 if the solution does not carry it. */
static int put_field(Writer *w, unsigned g, unsigned bit, const VnSolution *s) {
  switch (g * 16u + bit) {
    case 0u * 16u + 0u:
    case 1u * 16u + 0u:
      put_le(w, s->time_startup_ns, 8u);
      return 1;
    case 0u * 16u + 1u:
      put_le(w, s->time_gps_ns, 8u);
      return 1;
    case 0u * 16u + 3u:
      put_f32s(w, s->ypr_deg, 3u);
      return 1;
    case 0u * 16u + 4u:
      put_quaternion(w, s->ypr_deg);
      return 1;
    case 0u * 16u + 5u:
      put_f32s(w, s->angular_rate_radps, 3u);
      return 1;
    case 0u * 16u + 6u:
    case 5u * 16u + 1u:
      put_f64(w, s->lla[0]);
      put_f64(w, s->lla[1]);
      put_f64(w, s->lla[2]);
      return 1;
    case 0u * 16u + 7u:
    case 5u * 16u + 4u:
      put_f32s(w, s->vel_ned_mps, 3u);
      return 1;
    case 0u * 16u + 8u:
      put_f32s(w, s->accel_mps2, 3u);
      return 1;
    case 0u * 16u + 10u:
      put_f32s(w, s->mag_gauss, 3u);
      put_f32(w, s->temp_c);
      put_f32(w, s->pressure_kpa);
      return 1;
    case 0u * 16u + 12u:
    case 5u * 16u + 0u:
      put_le(w, s->ins_status, 2u);
      return 1;
    case 1u * 16u + 2u:
      put_le(w, s->time_gps_ns % NS_PER_WEEK, 8u);
      return 1;
    case 1u * 16u + 3u:
      /* 2^64 ns are 30,500 weeks: the week always fits its 16 bits. */
      put_le(w, s->time_gps_ns / NS_PER_WEEK, 2u);
      return 1;
    case 3u * 16u + 3u:
      put_u8(w, s->num_sats);
      return 1;
    case 3u * 16u + 4u:
      put_u8(w, s->gps_fix);
      return 1;
    case 3u * 16u + 9u:
      put_f32s(w, s->gps_pos_unc_m, 3u);
      return 1;
    case 3u * 16u + 10u:
      put_f32(w, s->gps_vel_unc_mps);
      return 1;
    case 4u * 16u + 8u:
      put_f32s(w, s->ypr_unc_deg, 3u);
      return 1;
    case 5u * 16u + 9u:
      put_f32(w, s->ins_pos_unc_m);
      return 1;
    case 5u * 16u + 10u:
      put_f32(w, s->ins_vel_unc_mps);
      return 1;
    default:
      return 0;
  }
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
