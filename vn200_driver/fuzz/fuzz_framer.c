/* libFuzzer harness: the framer over arbitrary bytes in arbitrary read sizes, then the decoders
 * over every frame it hands out. Beyond "no crash, no UB" it checks the framer's promises: a
 * frame fits the buffer, a binary frame always decodes (unless a value is NaN/inf), an ASCII
 * frame's checksum holds, and every input byte is accounted for (framed, dropped, or still
 * buffered). */
#include <stdint.h>
#include <stdlib.h>

#include "vn_ascii.h"
#include "vn_binary.h"
#include "vn_framer.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  static VnFramer f;
  size_t pos;
  size_t framed = 0u;
  uint8_t step;
  if (size < 1u) {
    return 0;
  }
  step = (uint8_t)(data[0] % 64u + 1u); /* read size chosen by the input */
  vn_framer_init(&f);
  for (pos = 1u; pos < size;) {
    size_t n = size - pos < step ? size - pos : step;
    size_t off = 0u;
    for (;;) {
      size_t used = 0u;
      VnFrame fr;
      int got = vn_framer_next(&f, data + pos + off, n - off, &used, &fr);
      off += used;
      if (off > n) {
        abort();
      }
      if (!got) {
        break;
      }
      if (fr.len == 0u || fr.len > VN_FRAME_MAX) {
        abort();
      }
      framed += fr.len;
      if (fr.kind == VN_FRAME_BINARY) {
        VnBinaryData d;
        VnBinResult r = vn_bin_decode(fr.data, fr.len, &d);
        /* Framing checked length and CRC; only field values can still be refused. */
        if (r != VN_BIN_OK && r != VN_BIN_ERR_NONFINITE) {
          abort();
        }
      } else {
        VnAsciiMsg m;
        if (!vn_ascii_checksum_ok((const char *)fr.data, fr.len)) {
          abort();
        }
        (void)vn_ascii_parse((const char *)fr.data, fr.len, &m);
      }
    }
    if (off != n) {
      abort(); /* a call that returns 0 must have taken all input */
    }
    pos += n;
  }
  /* Bytes of the last frame handed out stay in the buffer until the next call; count them once. */
  if (framed + f.stats.dropped_bytes + f.len - f.emitted != size - 1u) {
    abort();
  }
  return 0;
}
