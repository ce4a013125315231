#include "due_main.h"

#include <Arduino.h>

#include "../core/ha_aircraft.h"
#include "../core/ha_app.h"
#include "due_board.h"
#include "due_ins_seam.h"
#include "due_link.h"

namespace {

HaApp g_app;
DueBoard g_board;
uint32_t g_next_period_us = 0u;

}  // namespace

void due_main_setup(void) {
  const HaAircraftConfig *cfg = &ha_aircraft_config;
  due_board_begin(&g_board, cfg);
  ha_app_init(&g_app, cfg);
  /* The VN-200 on Serial1 feeds the core's state directly: see due_ins_seam.h. */
  due_ins_begin(cfg);
  /* After a watchdog or brown-out reset in flight: home, the airborne latch and the HA's latches
   * as they were (the SAM3X's backup registers, due_board.cpp). */
  ha_app_restore(&g_app, due_board_interface(&g_board), due_ins_adapter());
  due_link_begin(&g_app.inputs, &g_app.outputs);
  g_next_period_us = micros();
}

/* Runs as fast as loop() is called: the serial streams are drained every pass, and the control
 * period (cfg->period_us, 10 ms at 100 Hz) runs when its time has come. The time goes into the
 * core as micros(); the core handles the 32-bit wrap. */
void due_main_loop(void) {
  const HaAircraftConfig *cfg = &ha_aircraft_config;
  const uint32_t now_us = micros();
  due_ins_poll(&g_app.inputs, g_app.outputs.on_ground, now_us);
  due_link_poll(now_us);
  if (static_cast<int32_t>(now_us - g_next_period_us) < 0) {
    return;
  }
  ha_app_period(&g_app, due_board_interface(&g_board));
  due_link_publish(cfg, &g_app.inputs, &g_app.outputs, now_us);
  g_next_period_us += cfg->period_us;
  if (static_cast<int32_t>(now_us - g_next_period_us) >= 0) {
    /* More than a period behind (e.g. a long I2C stall): restart the schedule from now instead
     * of running a burst of catch-up periods. The core sees the longer period in its own dt. */
    g_next_period_us = now_us + cfg->period_us;
  }
}
