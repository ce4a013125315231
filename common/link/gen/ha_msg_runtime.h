/* Bounded little-endian primitives the generated message code (ha_msgs.c) is built on. Copied
 * next to it by make_c99_msgs.py, so the generated folder is self-contained for arduino-cli.
 * Every put/get checks the remaining room first and leaves *pos untouched on failure, so a
 * truncated or oversized message is refused rather than read past its end. C99, no heap. */
#ifndef HA_MSG_RUNTIME_H
#define HA_MSG_RUNTIME_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
  uint32_t sec;
  uint32_t nsec;
} HaRosTime;

typedef struct {
  int32_t sec;
  int32_t nsec;
} HaRosDuration;

/* A ROS string: bytes not owned (into the received frame, or a literal), not NUL-terminated. */
typedef struct {
  const char *data;
  uint32_t len;
} HaRosString;

static inline HaRosString ha_ros_string(const char *text) {
  HaRosString s;
  s.data = text;
  s.len = (text != NULL) ? (uint32_t)strlen(text) : 0u;
  return s;
}

static inline bool ha_room(size_t cap, const size_t *pos, size_t n) {
  return (*pos <= cap) && (n <= cap - *pos);
}

static inline bool ha_put_uint(uint8_t *out, size_t cap, size_t *pos, uint64_t v, size_t n) {
  size_t k;
  if (!ha_room(cap, pos, n)) {
    return false;
  }
  for (k = 0u; k < n; ++k) {
    out[*pos + k] = (uint8_t)((v >> (8u * k)) & 0xFFu);
  }
  *pos += n;
  return true;
}

static inline bool ha_get_uint(const uint8_t *in, size_t len, size_t *pos, uint64_t *v, size_t n) {
  size_t k;
  uint64_t acc = 0u;
  if (!ha_room(len, pos, n)) {
    return false;
  }
  for (k = 0u; k < n; ++k) {
    const size_t at = *pos + k;
    if (at >= len) { /* implied by ha_room; restated per byte so a value analysis sees it */
      return false;
    }
    acc |= ((uint64_t)in[at]) << (8u * k);
  }
  *pos += n;
  *v = acc;
  return true;
}

static inline bool ha_put_u8(uint8_t *o, size_t c, size_t *p, uint8_t v) {
  return ha_put_uint(o, c, p, v, 1u);
}
static inline bool ha_put_i8(uint8_t *o, size_t c, size_t *p, int8_t v) {
  return ha_put_uint(o, c, p, (uint8_t)v, 1u);
}
static inline bool ha_put_u16(uint8_t *o, size_t c, size_t *p, uint16_t v) {
  return ha_put_uint(o, c, p, v, 2u);
}
static inline bool ha_put_i16(uint8_t *o, size_t c, size_t *p, int16_t v) {
  return ha_put_uint(o, c, p, (uint16_t)v, 2u);
}
static inline bool ha_put_u32(uint8_t *o, size_t c, size_t *p, uint32_t v) {
  return ha_put_uint(o, c, p, v, 4u);
}
static inline bool ha_put_i32(uint8_t *o, size_t c, size_t *p, int32_t v) {
  return ha_put_uint(o, c, p, (uint32_t)v, 4u);
}
static inline bool ha_put_u64(uint8_t *o, size_t c, size_t *p, uint64_t v) {
  return ha_put_uint(o, c, p, v, 8u);
}
static inline bool ha_put_i64(uint8_t *o, size_t c, size_t *p, int64_t v) {
  return ha_put_uint(o, c, p, (uint64_t)v, 8u);
}

static inline bool ha_put_f32(uint8_t *o, size_t c, size_t *p, float v) {
  uint32_t bits;
  memcpy(&bits, &v, sizeof bits); /* the defined way to read IEEE-754 bits in C99 */
  return ha_put_uint(o, c, p, bits, 4u);
}

static inline bool ha_put_f64(uint8_t *o, size_t c, size_t *p, double v) {
  uint64_t bits;
  memcpy(&bits, &v, sizeof bits);
  return ha_put_uint(o, c, p, bits, 8u);
}

static inline bool ha_put_time(uint8_t *o, size_t c, size_t *p, const HaRosTime *t) {
  size_t q = *p;
  if (!ha_put_u32(o, c, &q, t->sec) || !ha_put_u32(o, c, &q, t->nsec)) {
    return false;
  }
  *p = q;
  return true;
}

static inline bool ha_put_duration(uint8_t *o, size_t c, size_t *p, const HaRosDuration *t) {
  size_t q = *p;
  if (!ha_put_i32(o, c, &q, t->sec) || !ha_put_i32(o, c, &q, t->nsec)) {
    return false;
  }
  *p = q;
  return true;
}

static inline bool ha_put_string(uint8_t *o, size_t c, size_t *p, const HaRosString *s) {
  size_t q = *p;
  if ((s->len > 0u) && (s->data == NULL)) {
    return false;
  }
  if (!ha_put_u32(o, c, &q, s->len) || !ha_room(c, &q, s->len)) {
    return false;
  }
  if (s->len > 0u) {
    memcpy(&o[q], s->data, s->len);
  }
  *p = q + s->len;
  return true;
}

#define HA_GET_AS(name, type, n)                                                     \
  static inline bool ha_get_##name(const uint8_t *i, size_t l, size_t *p, type *v) { \
    uint64_t raw = 0u; /* defined on every path, for the analyzer too */             \
    if (!ha_get_uint(i, l, p, &raw, n)) {                                            \
      return false;                                                                  \
    }                                                                                \
    *v = (type)raw;                                                                  \
    return true;                                                                     \
  }
HA_GET_AS(u8, uint8_t, 1u)
HA_GET_AS(u16, uint16_t, 2u)
HA_GET_AS(u32, uint32_t, 4u)
HA_GET_AS(u64, uint64_t, 8u)
#undef HA_GET_AS

static inline bool ha_get_i8(const uint8_t *i, size_t l, size_t *p, int8_t *v) {
  uint8_t u = 0u;
  if (!ha_get_u8(i, l, p, &u)) {
    return false;
  }
  memcpy(v, &u, 1u); /* two's complement reinterpretation without implementation-defined casts */
  return true;
}
static inline bool ha_get_i16(const uint8_t *i, size_t l, size_t *p, int16_t *v) {
  uint16_t u = 0u;
  if (!ha_get_u16(i, l, p, &u)) {
    return false;
  }
  memcpy(v, &u, 2u);
  return true;
}
static inline bool ha_get_i32(const uint8_t *i, size_t l, size_t *p, int32_t *v) {
  uint32_t u = 0u;
  if (!ha_get_u32(i, l, p, &u)) {
    return false;
  }
  memcpy(v, &u, 4u);
  return true;
}
static inline bool ha_get_i64(const uint8_t *i, size_t l, size_t *p, int64_t *v) {
  uint64_t u = 0u;
  if (!ha_get_u64(i, l, p, &u)) {
    return false;
  }
  memcpy(v, &u, 8u);
  return true;
}
static inline bool ha_get_f32(const uint8_t *i, size_t l, size_t *p, float *v) {
  uint32_t u = 0u;
  if (!ha_get_u32(i, l, p, &u)) {
    return false;
  }
  memcpy(v, &u, 4u);
  return true;
}
static inline bool ha_get_f64(const uint8_t *i, size_t l, size_t *p, double *v) {
  uint64_t u = 0u;
  if (!ha_get_u64(i, l, p, &u)) {
    return false;
  }
  memcpy(v, &u, 8u);
  return true;
}
static inline bool ha_get_time(const uint8_t *i, size_t l, size_t *p, HaRosTime *t) {
  size_t q = *p;
  if (!ha_get_u32(i, l, &q, &t->sec) || !ha_get_u32(i, l, &q, &t->nsec)) {
    return false;
  }
  *p = q;
  return true;
}
static inline bool ha_get_duration(const uint8_t *i, size_t l, size_t *p, HaRosDuration *t) {
  size_t q = *p;
  if (!ha_get_i32(i, l, &q, &t->sec) || !ha_get_i32(i, l, &q, &t->nsec)) {
    return false;
  }
  *p = q;
  return true;
}
static inline bool ha_get_string(const uint8_t *i, size_t l, size_t *p, HaRosString *s) {
  size_t q = *p;
  uint32_t n = 0u;
  if (!ha_get_u32(i, l, &q, &n) || !ha_room(l, &q, n)) {
    return false;
  }
  s->data = (const char *)&i[q];
  s->len = n;
  *p = q + n;
  return true;
}

#ifdef __cplusplus
}
#endif

#endif /* HA_MSG_RUNTIME_H */
