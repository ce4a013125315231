/* Frama-C EVA analysis driver for the VN-200 protocol core (common/vn200). Not compiled
 * into anything: make verify-vn200-eva (tools/eva.sh) hands it to frama-c with every .c of the
 * core. Every input is unknown: the bytes the framer reads (in several reads of any length), the
 * packet and sentence bytes and lengths given to the decoders, and every field of the command
 * builders' arguments. EVA must then find no run-time error (overflow, out-of-bounds access,
 * invalid shift, uninitialised read, invalid float conversion) on any of them. */
#include <stddef.h>
#include <stdint.h>

#include "__fc_builtin.h"
#include "vn_ascii.h"
#include "vn_binary.h"
#include "vn_checksum.h"
#include "vn_command.h"
#include "vn_framer.h"

#ifndef READ_MAX
#define READ_MAX 16u
#endif
#ifndef READS
#define READS 40
#endif

/* One entry point per part (main_framer, main_binary, main_ascii, main_commands), so
 * tools/eva.sh analyses each with its own precision budget. */
static VnFramer framer;
static uint8_t rx[READ_MAX];
static uint8_t pkt[VN_BIN_MAX_PACKET + 8u];
static char text[VN_ASCII_MAX + 8u];
static char cmd[VN_CMD_MAX];

void main_framer(void) {
  int r;
  vn_framer_init(&framer);
  /* Every call gets a fresh unknown read of unknown length: the unread rest of a real read is
   * one such input, so this covers any sequence of reads, frames and resynchronisations. */
  for (r = 0; r < READS; ++r) {
    size_t used = 0u;
    VnFrame fr;
    size_t len = Frama_C_unsigned_int_interval(0u, READ_MAX);
    Frama_C_make_unknown((char *)rx, READ_MAX);
    (void)vn_framer_next(&framer, rx, len, &used, &fr);
  }
}

void main_binary(void) {
  VnBinaryData d;
  size_t len;
  Frama_C_make_unknown((char *)pkt, sizeof pkt);
  len = Frama_C_unsigned_int_interval(0u, sizeof pkt);
  (void)vn_bin_decode(pkt, len, &d);
}

void main_ascii(void) {
  VnAsciiMsg m;
  double v = 0.0;
  uint32_t u = 0u;
  size_t len;
  unsigned i;
  Frama_C_make_unknown(text, sizeof text);
  len = Frama_C_unsigned_int_interval(0u, sizeof text);
  if (vn_ascii_parse(text, len, &m) == VN_ASCII_OK) {
    for (i = 0u; i < m.field_count && i < VN_ASCII_MAX_FIELDS; ++i) {
      (void)vn_ascii_field_f64(text, &m, i, &v);
      (void)vn_ascii_field_u32(text, &m, i, 16u, &u);
    }
  }
  (void)vn_ascii_checksum_ok(text, len);
  (void)vn_parse_f64(text, len, &v);
}

void main_commands(void) {
  VnBinaryOutputConfig cfg;
  size_t cap = Frama_C_unsigned_int_interval(0u, sizeof cmd);
  VnChecksumMode ck = Frama_C_nondet(0, 1) ? VN_CK_CRC16 : VN_CK_XOR8;
  Frama_C_make_unknown((char *)&cfg, sizeof cfg);
  (void)vn_cmd_binary_output(cmd, cap, &cfg, ck);
  (void)vn_cmd_set_baud(cmd, cap, Frama_C_unsigned_int_interval(0u, UINT32_MAX), ck);
  (void)vn_cmd_read_register(cmd, cap, Frama_C_unsigned_int_interval(0u, 300u), ck);
  (void)vn_cmd_async_off(cmd, cap, ck);
}
