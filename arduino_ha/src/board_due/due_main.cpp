#include "due_main.h"

#include "../core/ha_aircraft.h"
#include "../firmware/ha_firmware.h"
#include "due_board.h"

namespace {

DueBoard g_board;
HaFirmware g_firmware;

}  // namespace

void due_main_setup(void) {
  HaFirmwareOptions opts = HaFirmwareOptions();
  opts.link_up_text = "HA Due link up";
  due_board_begin(&g_board, &ha_aircraft_config);
  /* After a watchdog or brown-out reset in flight the firmware takes back home and the HA's
   * latches from the SAM3X's backup registers (due_board.cpp). */
  ha_firmware_start(&g_firmware, due_board_interface(&g_board), &ha_aircraft_config, &opts);
}

/* Runs as fast as loop() is called: the serial ports are drained every pass, and the control
 * period (cfg->period_us, 10 ms at 100 Hz) runs when its time has come (src/firmware/). */
void due_main_loop(void) { (void)ha_firmware_loop(&g_firmware); }

const HaFirmware *due_main_firmware(void) { return &g_firmware; }
