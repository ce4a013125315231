#include "due_main.h"

#include <Arduino.h>

#include "../core/ha_aircraft.h"
#include "../firmware/ha_firmware.h"
#include "due_config.h"
#if HA_DUE_HIL
#include "due_hil_board.h"
#else
#include "due_board.h"
#endif

namespace {

#if HA_DUE_HIL
DueHilBoard g_board;
#else
DueBoard g_board;
#endif
HaFirmware g_firmware;

/* Power-up, and in the HIL build a reset record: the firmware afresh over the same board. After a
 * watchdog or brown-out reset in flight the firmware takes back home and the HA's latches from the
 * SAM3X's backup registers (due_common.cpp). */
void start_firmware(void) {
  HaFirmwareOptions opts = HaFirmwareOptions();
  opts.pace_by_command = 1;  // on its own clock: a period runs on the HP command's arrival
#if HA_DUE_HIL
  opts.link_up_text = "HA Due HIL link up";
  opts.command_tap = due_hil_board_count_command;
  opts.tap_ctx = &g_board;
  ha_firmware_start(&g_firmware, due_hil_board_interface(&g_board), &ha_aircraft_config, &opts);
#else
  opts.link_up_text = "HA Due link up";
  ha_firmware_start(&g_firmware, due_board_interface(&g_board), &ha_aircraft_config, &opts);
#endif
}

}  // namespace

void due_main_setup(void) {
#if HA_DUE_HIL
  due_hil_board_begin(&g_board);
#else
  due_board_begin(&g_board, &ha_aircraft_config);
#endif
  start_firmware();
}

/* Runs as fast as loop() is called: the serial ports are drained every pass, and the control
 * period (cfg->period_us, 10 ms at 100 Hz) runs when its time has come (src/firmware/). The HIL
 * build takes the simulator's records first, so a period runs on the latest inputs, and answers
 * each period it ran. */
void due_main_loop(void) {
#if HA_DUE_HIL
  if (due_hil_board_take_records(&g_board) == DUE_HIL_RESET) {
    start_firmware();
  }
  const uint32_t pass_start_us = micros();
  if (ha_firmware_loop(&g_firmware)) {
    due_hil_board_reply(&g_board, &g_firmware, micros() - pass_start_us);
  }
#else
  (void)ha_firmware_loop(&g_firmware);
#endif
}

const HaFirmware *due_main_firmware(void) { return &g_firmware; }
