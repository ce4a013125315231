#include "vn_ascii.h"

#include <float.h>
#include <string.h>

#include "vn_checksum.h"

static int hex_val(char c) {
  if (c >= '0' && c <= '9') {
    return c - '0';
  }
  if (c >= 'A' && c <= 'F') {
    return c - 'A' + 10;
  }
  if (c >= 'a' && c <= 'f') {
    return c - 'a' + 10;
  }
  return -1;
}

/* The parsers index the sentence itself between begin and end, never a pointer into its
 * middle: bounds then follow from end <= length, which Frama-C EVA can check. */
static int parse_u32_range(const char *s, size_t begin, size_t end, unsigned base, uint32_t *out) {
  uint32_t v = 0u;
  size_t i;
  if (end <= begin || end - begin > 10u || (base != 10u && base != 16u)) {
    return 0;
  }
  for (i = begin; i < end; ++i) {
    int d = hex_val(s[i]);
    if (d < 0 || (unsigned)d >= base) {
      return 0;
    }
    if (v > (UINT32_MAX - (uint32_t)d) / base) {
      return 0;
    }
    v = v * base + (uint32_t)d;
  }
  *out = v;
  return 1;
}

int vn_parse_u32(const char *s, size_t len, unsigned base, uint32_t *out) {
  if (s == NULL || out == NULL) {
    return 0;
  }
  return parse_u32_range(s, 0u, len, base, out);
}

/* The exponent after s[*i] == 'e': a sign and one to three digits, in [-999, 999]; moves *i
 * past it. 0 if malformed. */
static int read_exponent(const char *s, size_t *i, size_t len, int *exp_out) {
  int eneg = 0;
  int e = 0;
  int edigits = 0;
  size_t k = *i + 1u;
  if (k < len && (s[k] == '+' || s[k] == '-')) {
    eneg = s[k] == '-';
    ++k;
  }
  for (; k < len && s[k] >= '0' && s[k] <= '9'; ++k) {
    if (edigits >= 3) {
      return 0;
    }
    e = e * 10 + (s[k] - '0');
    ++edigits;
  }
  if (edigits == 0) {
    return 0;
  }
  *exp_out = eneg ? -e : e;
  *i = k;
  return 1;
}

/* mant x 10^exp10, exp10 in [-340, 20]. Bounded scaling loops; dividing keeps "+010.071"
 * exactly as close as strtod to 1 ulp. */
static double scaled(uint64_t mant, int exp10) {
  double v = (double)mant;
  while (exp10 > 0) {
    v *= 10.0;
    --exp10;
  }
  while (exp10 < 0) {
    v /= 10.0;
    ++exp10;
  }
  return v;
}

/* Reads the digits from *i on into *mant, the first 18 significant ones (more than a double
 * holds): *kept counts the digits read into it, *dropped those read past them. Returns whether
 * any digit was read. The caller's 40-character bound keeps the counts below 64; the caps say
 * so to the analysis. */
static int read_digits(const char *s, size_t *i, size_t end, uint64_t *mant, int *mant_digits,
                       int *kept, int *dropped) {
  size_t k = *i;
  int in = 0;
  int out = 0;
  for (; k < end && s[k] >= '0' && s[k] <= '9'; ++k) {
    if (*mant_digits < 18) {
      *mant = *mant * 10u + (uint64_t)(s[k] - '0');
      if (*mant != 0u) {
        ++*mant_digits;
      }
      in += in < 64;
    } else {
      out += out < 64;
    }
  }
  *i = k;
  *kept = in;
  *dropped = out;
  return in + out > 0;
}

static int parse_f64_range(const char *s, size_t begin, size_t end, double *out) {
  size_t i = begin;
  int neg = 0;
  uint64_t mant = 0u;
  int mant_digits = 0;
  int exp10 = 0;
  int any_digit = 0;
  int kept = 0;
  int dropped = 0;
  int e = 0;
  double v;
  if (end <= begin || end - begin > 40u) {
    return 0;
  }
  if (s[i] == '+' || s[i] == '-') {
    neg = s[i] == '-';
    ++i;
  }
  any_digit = read_digits(s, &i, end, &mant, &mant_digits, &kept, &dropped);
  exp10 += dropped; /* integer digits beyond double precision only scale */
  if (i < end && s[i] == '.') {
    ++i;
    any_digit |= read_digits(s, &i, end, &mant, &mant_digits, &kept, &dropped);
    exp10 -= kept; /* fraction digits beyond it are dropped */
  }
  if (!any_digit) {
    return 0;
  }
  if (i < end && (s[i] == 'e' || s[i] == 'E')) {
    if (!read_exponent(s, &i, end, &e)) {
      return 0;
    }
    exp10 += e;
  }
  if (i != end) {
    return 0;
  }
  /* The sensor never sends numbers beyond 1e38 (the float range its fields have); refusing
   * larger scales keeps every result finite: mant < 2^64 times 10^20 stays below 2e39. */
  if (exp10 > 20 || exp10 < -340) {
    return 0;
  }
  v = scaled(mant, exp10);
  *out = neg ? -v : v;
  return 1;
}

int vn_parse_f64(const char *s, size_t len, double *out) {
  if (s == NULL || out == NULL) {
    return 0;
  }
  return parse_f64_range(s, 0u, len, out);
}

/* Length without a trailing "\r\n" (or lone "\n"). */
static size_t trim_eol(const char *s, size_t len) {
  if (len > 0u && s[len - 1u] == '\n') {
    --len;
  }
  if (len > 0u && s[len - 1u] == '\r') {
    --len;
  }
  return len;
}

/* Index of the last '*', or len when there is none. */
static size_t find_star(const char *s, size_t len) {
  size_t i = len;
  while (i > 0u) {
    --i;
    if (s[i] == '*') {
      return i;
    }
  }
  return len;
}

int vn_ascii_checksum_ok(const char *s, size_t len) {
  size_t star;
  size_t tail;
  uint32_t sent = 0u;
  if (s == NULL) {
    return 0;
  }
  len = trim_eol(s, len);
  if (len < 2u || s[0] != '$') {
    return 0;
  }
  star = find_star(s, len);
  if (star == len) {
    return 0;
  }
  tail = len - star - 1u;
  if (tail == 2u && s[len - 2u] == 'X' && s[len - 1u] == 'X') {
    return 1;
  }
  if ((tail != 2u && tail != 4u) || !parse_u32_range(s, star + 1u, len, 16u, &sent)) {
    return 0;
  }
  if (tail == 2u) {
    return vn_xor8((const uint8_t *)(s + 1), star - 1u) == (uint8_t)sent;
  }
  return vn_crc16((const uint8_t *)(s + 1), star - 1u) == (uint16_t)sent;
}

/* Field idx's [*begin, *end) in s; 0 for a field the message does not have. */
static int field_range(const char *s, const VnAsciiMsg *m, unsigned idx, size_t *begin,
                       size_t *end) {
  size_t b;
  size_t e;
  if (s == NULL || m == NULL || idx >= m->field_count || idx >= VN_ASCII_MAX_FIELDS) {
    return 0;
  }
  b = m->field_off[idx];
  e = b + m->field_len[idx];
  if (e > m->len) {
    return 0;
  }
  *begin = b;
  *end = e;
  return 1;
}

int vn_ascii_field_u32(const char *s, const VnAsciiMsg *m, unsigned idx, unsigned base,
                       uint32_t *out) {
  size_t begin = 0u;
  size_t end = 0u;
  return out != NULL && field_range(s, m, idx, &begin, &end) &&
         parse_u32_range(s, begin, end, base, out);
}

int vn_ascii_field_f64(const char *s, const VnAsciiMsg *m, unsigned idx, double *out) {
  size_t begin = 0u;
  size_t end = 0u;
  return out != NULL && field_range(s, m, idx, &begin, &end) && parse_f64_range(s, begin, end, out);
}

static int field_f32(const char *s, const VnAsciiMsg *m, unsigned idx, float *out) {
  double d = 0.0;
  /* Converting a double outside the float range is undefined behaviour in C: refuse it. */
  if (!vn_ascii_field_f64(s, m, idx, &d) || d > (double)FLT_MAX || d < -(double)FLT_MAX) {
    return 0;
  }
  *out = (float)d;
  return 1;
}

static VnAsciiResult decode_ins(const char *s, VnAsciiMsg *m) {
  /* $VNINS,tow,week,status(hex),yaw,pitch,roll,lat,lon,alt,velN,velE,velD,attU,posU,velU */
  VnAsciiIns *d = &m->ins;
  uint32_t u = 0u;
  unsigned i;
  if (m->field_count != 15u || !vn_ascii_field_f64(s, m, 0u, &d->tow_s)) {
    return VN_ASCII_ERR_FIELDS;
  }
  if (!vn_ascii_field_u32(s, m, 1u, 10u, &u) || u > 0xFFFFu) {
    return VN_ASCII_ERR_FIELDS;
  }
  d->week = (uint16_t)u;
  if (!vn_ascii_field_u32(s, m, 2u, 16u, &u) || u > 0xFFFFu) {
    return VN_ASCII_ERR_FIELDS;
  }
  d->ins_status = (uint16_t)u;
  for (i = 0u; i < 3u; ++i) {
    if (!field_f32(s, m, 3u + i, &d->ypr_deg[i]) || !field_f32(s, m, 9u + i, &d->vel_ned_mps[i])) {
      return VN_ASCII_ERR_FIELDS;
    }
  }
  if (!vn_ascii_field_f64(s, m, 6u, &d->lat_deg) || !vn_ascii_field_f64(s, m, 7u, &d->lon_deg) ||
      !vn_ascii_field_f64(s, m, 8u, &d->alt_m) || !field_f32(s, m, 12u, &d->att_unc_deg) ||
      !field_f32(s, m, 13u, &d->pos_unc_m) || !field_f32(s, m, 14u, &d->vel_unc_mps)) {
    return VN_ASCII_ERR_FIELDS;
  }
  return VN_ASCII_OK;
}

static VnAsciiResult decode_known(const char *s, VnAsciiMsg *m) {
  uint32_t u = 0u;
  unsigned i;
  if (strcmp(m->header, "VNYPR") == 0) {
    m->kind = VN_ASCII_YPR;
    if (m->field_count != 3u) {
      return VN_ASCII_ERR_FIELDS;
    }
    for (i = 0u; i < 3u; ++i) {
      if (!field_f32(s, m, i, &m->ypr_deg[i])) {
        return VN_ASCII_ERR_FIELDS;
      }
    }
    return VN_ASCII_OK;
  }
  if (strcmp(m->header, "VNINS") == 0) {
    m->kind = VN_ASCII_INS_LLA;
    return decode_ins(s, m);
  }
  if (strcmp(m->header, "VNRRG") == 0 || strcmp(m->header, "VNWRG") == 0) {
    m->kind = m->header[2] == 'R' ? VN_ASCII_READ_REG : VN_ASCII_WRITE_REG;
    if (m->field_count < 1u || !vn_ascii_field_u32(s, m, 0u, 10u, &u) || u > 255u) {
      return VN_ASCII_ERR_FIELDS;
    }
    m->reg_id = (uint16_t)u;
    return VN_ASCII_OK;
  }
  if (strcmp(m->header, "VNERR") == 0) {
    m->kind = VN_ASCII_ERROR;
    if (m->field_count != 1u || !vn_ascii_field_u32(s, m, 0u, 16u, &u) || u > 255u) {
      return VN_ASCII_ERR_FIELDS;
    }
    m->error_code = (uint8_t)u;
    return VN_ASCII_OK;
  }
  m->kind = VN_ASCII_UNKNOWN;
  return VN_ASCII_OK;
}

VnAsciiResult vn_ascii_parse(const char *s, size_t len, VnAsciiMsg *out) {
  size_t star;
  size_t i;
  size_t start;
  if (out == NULL) {
    return VN_ASCII_ERR_NULL;
  }
  memset(out, 0, sizeof *out);
  if (s == NULL) {
    return VN_ASCII_ERR_NULL;
  }
  len = trim_eol(s, len);
  if (len < 2u || len > 0xFFFFu || s[0] != '$') {
    return VN_ASCII_ERR_FORMAT;
  }
  star = find_star(s, len);
  if (star == len) {
    return VN_ASCII_ERR_FORMAT;
  }
  for (i = 1u; i < star; ++i) {
    if (s[i] < 0x20 || s[i] > 0x7E || s[i] == '$' || s[i] == '*') {
      return VN_ASCII_ERR_FORMAT;
    }
  }
  if (!vn_ascii_checksum_ok(s, len)) {
    return VN_ASCII_ERR_CHECKSUM;
  }
  /* Header: up to the first comma or the '*'. */
  start = 1u;
  i = start;
  while (i < star && s[i] != ',') {
    ++i;
  }
  if (i == start || i - start >= sizeof out->header) {
    return VN_ASCII_ERR_FORMAT;
  }
  out->len = (uint16_t)len;
  memcpy(out->header, s + start, i - start);
  out->header[i - start] = '\0';
  /* Fields: each comma opens one; an empty field is legal syntax (its parse will fail). */
  while (i < star) {
    size_t f = i + 1u;
    size_t e = f;
    while (e < star && s[e] != ',') {
      ++e;
    }
    if (out->field_count >= VN_ASCII_MAX_FIELDS || e - f > 255u) {
      return VN_ASCII_ERR_FORMAT;
    }
    out->field_off[out->field_count] = (uint16_t)f;
    out->field_len[out->field_count] = (uint8_t)(e - f);
    ++out->field_count;
    i = e;
  }
  return decode_known(s, out);
}
