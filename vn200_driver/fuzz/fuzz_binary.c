/* libFuzzer harness: the binary decoder on arbitrary packets. The first bytes may be patched
 * into a valid CRC so the fuzzer reaches the field decoding, not only the CRC check. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "vn_binary.h"
#include "vn_checksum.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  static uint8_t buf[VN_BIN_MAX_PACKET + 16u];
  VnBinaryData d;
  VnBinResult r;
  size_t n;
  if (size < 1u) {
    return 0;
  }
  r = vn_bin_decode(data + 1, size - 1u, &d); /* as given */
  (void)r;
  n = size - 1u;
  if (n < 3u || n > sizeof buf) {
    return 0;
  }
  memcpy(buf, data + 1, n);
  buf[0] = VN_BIN_SYNC;
  if (data[0] & 1u) { /* fix the CRC */
    uint16_t crc = vn_crc16(buf + 1, n - 3u);
    buf[n - 2u] = (uint8_t)(crc >> 8);
    buf[n - 1u] = (uint8_t)crc;
  }
  r = vn_bin_decode(buf, n, &d);
  if (r == VN_BIN_OK) {
    uint16_t masks[VN_BIN_GROUP_COUNT];
    size_t k = 0u;
    unsigned g;
    for (g = 0u; g < VN_BIN_GROUP_COUNT; ++g) {
      if (d.groups & (1u << g)) {
        masks[k++] = d.masks[g];
      }
    }
    if (vn_bin_packet_len(d.groups, masks, k) != n || n > VN_BIN_MAX_PACKET) {
      abort();
    }
  }
  return 0;
}
