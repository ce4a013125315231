/* Frama-C EVA analysis driver for the firmware loop (arduino_ha/src/firmware) with everything it
 * runs: the core, the link and its reports, the VN-200 feed and the VN-200 protocol core. Not
 * compiled into anything: make verify-ha-fw-eva (part of make verify-ha, tools/eva.sh) hands
 * it to frama-c with those sources.
 *
 * The board is as hostile as its types allow: its clock jumps anywhere, every reading is any
 * value, the retained words hold anything, and its two byte ports deliver any bytes, any number of
 * them per read (also more than asked for, which the loop must not trust). The loop runs an
 * unknown number of passes (each a receive, the service and, or not, a period: what the SIL in
 * lockstep calls too), mixed with drains of any length and with resets (the firmware started again
 * on the same board). EVA must find no run-time error, and every servo value the board is handed
 * must be finite and inside S_u. */
#define HA_EVA_ANY_BITS /* the board's floats any bit pattern, as the VN-200's bytes are */
#include <stddef.h>
#include <stdint.h>

#include "__fc_builtin.h"
#include "eva_board.h"
#include "ha_aircraft.h"
#include "ha_firmware.h"

/* Any bytes, any count: within what was asked, or a board that claims more. */
static size_t fw_port_read(void *ctx, uint8_t *bytes, size_t max_len) {
  (void)ctx;
  Frama_C_make_unknown((char *)bytes, max_len);
  return Frama_C_unsigned_int_interval(0u, UINT32_MAX);
}
static void fw_port_write(void *ctx, const uint8_t *bytes, size_t len) {
  (void)ctx;
  /* What a UART would do with them: read each one. */
  if (len > 0u) {
    volatile uint8_t last = bytes[len - 1u];
    (void)last;
  }
}

int main(void) {
  static HaFirmware fw;
  static const HaBoard board = {.ctx = NULL,
                                HA_EVA_BOARD_ENTRIES,
                                .hp_link = {fw_port_read, fw_port_write},
                                .ins = {fw_port_read, NULL}};
  HaFirmwareOptions opts = {"HA EVA link up", "rate_hz", 0u, 0u, NULL, NULL};
  opts.period_us = Frama_C_unsigned_int_interval(0u, UINT32_MAX);
  opts.reads_per_pass = Frama_C_unsigned_int_interval(0u, 8u);
  opts.pace_by_command = Frama_C_interval(0, 1); /* on a clock, or on the command's arrival */
  ha_firmware_start(&fw, &board, &ha_aircraft_config, &opts);
  while (Frama_C_nondet(0, 1)) {
    switch (Frama_C_interval(0, 3)) {
      case 0:
        (void)ha_firmware_loop(&fw);
        break;
      case 1: /* a board with the simulator's schedule drains the ports until they are empty */
        (void)ha_firmware_receive(&fw, any_u32(), any_u32());
        break;
      case 2:
        ha_firmware_start(&fw, &board, &ha_aircraft_config, &opts); /* a reset */
        break;
      default:
        (void)ha_firmware_link_errors(&fw.link);
        break;
    }
    check_servo_command(&fw.app.outputs.surfaces);
  }
  return 0;
}
