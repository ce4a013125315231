#include "ha_app.h"

#include <string.h>

void ha_app_init(HaApp *app, const HaAircraftConfig *cfg) {
  memset(app, 0, sizeof *app);
  ha_core_init(&app->core, cfg);
  /* Before the first period the HA is in charge and the servos idle. */
  app->outputs.controller = HA_CONTROLLER_HA;
  app->outputs.surfaces.throttle = cfg->throttle_min;
  app->outputs.leds = HA_LED_HA;
}

/* A failed reading enters the core as -1: below every valid airspeed (and voltage), so the
 * range checks reject it, without the core ever seeing a NaN it did not make itself. */
static float reading_or_invalid(int ok, float value) { return ok ? value : -1.0f; }

void ha_app_period(HaApp *app, const HaBoard *board) {
  float airspeed_ftps = 0.0f;
  float battery_v = 0.0f;
  const uint32_t now_us = board->micros(board->ctx);
  const int airspeed_ok = board->read_airspeed_ftps(board->ctx, &airspeed_ftps);
  const int battery_ok = board->read_battery_v(board->ctx, &battery_v);
  board->read_rc(board->ctx, &app->inputs.rc);
  app->inputs.airspeed_ftps = reading_or_invalid(airspeed_ok, airspeed_ftps);
  app->inputs.battery_v = reading_or_invalid(battery_ok, battery_v);
  ha_core_step(&app->core, &app->inputs, now_us, &app->outputs);
  board->write_servos(board->ctx, &app->outputs.surfaces);
  board->set_hp_reset(board->ctx, app->outputs.hp_reset_asserted);
  board->set_leds(board->ctx, app->outputs.leds);
  board->kick_watchdog(board->ctx);
}
