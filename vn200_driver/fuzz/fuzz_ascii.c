/* libFuzzer harness: ASCII sentence parsing and the number parsers on arbitrary text. With the
 * first byte odd the harness appends a correct XOR checksum so parsing reaches the fields. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vn_ascii.h"
#include "vn_checksum.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  static char buf[600];
  VnAsciiMsg m;
  double d;
  uint32_t u;
  size_t n;
  if (size < 1u) {
    return 0;
  }
  (void)vn_ascii_parse((const char *)data + 1, size - 1u, &m);
  (void)vn_parse_f64((const char *)data + 1, size - 1u, &d);
  (void)vn_parse_u32((const char *)data + 1, size - 1u, 10u, &u);
  (void)vn_parse_u32((const char *)data + 1, size - 1u, 16u, &u);
  n = size - 1u;
  if ((data[0] & 1u) && n + 6u < sizeof buf) {
    static const char hex[] = "0123456789ABCDEF";
    uint8_t x;
    buf[0] = '$';
    memcpy(buf + 1, data + 1, n);
    x = vn_xor8((const uint8_t *)buf + 1, n);
    buf[n + 1u] = '*';
    buf[n + 2u] = hex[x >> 4];
    buf[n + 3u] = hex[x & 0xFu];
    buf[n + 4u] = '\r';
    buf[n + 5u] = '\n';
    if (vn_ascii_parse(buf, n + 6u, &m) == VN_ASCII_OK) {
      unsigned i;
      for (i = 0u; i < m.field_count; ++i) {
        if ((size_t)m.field_off[i] + m.field_len[i] > n + 1u) {
          abort(); /* a field must lie inside the sentence body */
        }
        (void)vn_ascii_field_f64(buf, &m, i, &d);
      }
    }
  }
  return 0;
}
