/* libFuzzer harness: command builders on arbitrary arguments. Whatever they build must parse
 * back as a well-formed, correctly checksummed register write of the intended register. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "vn_ascii.h"
#include "vn_command.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  VnBinaryOutputConfig cfg;
  char buf[VN_CMD_MAX];
  VnAsciiMsg m;
  size_t n;
  size_t cap;
  uint32_t baud;
  VnChecksumMode ck;
  if (size < 20u) {
    return 0;
  }
  memset(&cfg, 0, sizeof cfg);
  cfg.output = data[0];
  cfg.async_mode = data[1];
  cfg.rate_divisor = (uint16_t)(data[2] | (data[3] << 8));
  cfg.groups = data[4];
  memcpy(cfg.masks, data + 5, sizeof cfg.masks);
  ck = (data[17] & 1u) ? VN_CK_CRC16 : VN_CK_XOR8;
  cap = (size_t)data[18] % (sizeof buf + 1u);
  n = vn_cmd_binary_output(buf, cap, &cfg, ck);
  if (n > 0u) {
    if (n > cap || vn_ascii_parse(buf, n, &m) != VN_ASCII_OK || m.kind != VN_ASCII_WRITE_REG ||
        m.reg_id != 74u + cfg.output || vn_binary_output_packet_len(&cfg) == 0u) {
      abort();
    }
  }
  baud = (uint32_t)data[19] * 4800u;
  n = vn_cmd_set_baud(buf, cap, baud, ck);
  if (n > 0u && (n > cap || vn_ascii_parse(buf, n, &m) != VN_ASCII_OK || m.reg_id != 5u)) {
    abort();
  }
  n = vn_cmd_read_register(buf, cap, data[5], ck);
  if (n > 0u && (n > cap || !vn_ascii_checksum_ok(buf, n))) {
    abort();
  }
  return 0;
}
