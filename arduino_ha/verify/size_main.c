/* The smallest program that contains everything the Due firmware takes from the HA core:
 * ha_app_init and ha_app_restore once, then ha_app_period against a board, as the sketch's 100 Hz
 * loop does. Linked by verify/cross_size.sh so the reported flash and RAM are what the core costs
 * on a Cortex-M3 (its code, the soft-float routines it pulls from libgcc, its state), not a guess
 * from object files. The board here does nothing; the real one is src/board_due/. */
#include <stddef.h>
#include <stdint.h>

#include "ha_aircraft.h"
#include "ha_app.h"
#include "null_outputs.h"

static volatile uint32_t fake_clock_us;

static uint32_t size_micros(void *ctx) {
  (void)ctx;
  return fake_clock_us;
}
static volatile uint16_t servo_pulses_us[HA_U_DIM];

static void size_write_servos(void *ctx, const HaSurfaces *surfaces) {
  uint16_t pulses_us[HA_U_DIM];
  uint32_t i;
  (void)ctx;
  /* The Due layer converts with this core helper, so its cost belongs in the image. */
  ha_surfaces_to_pulses_us(&ha_aircraft_config, surfaces, pulses_us);
  for (i = 0u; i < (uint32_t)HA_U_DIM; ++i) {
    servo_pulses_us[i] = pulses_us[i];
  }
}
static void size_read_rc(void *ctx, HaRcInputs *rc) {
  (void)ctx;
  rc->valid = 0u;
}
static int size_read_airspeed_ftps(void *ctx, float *airspeed_ftps) {
  (void)ctx;
  *airspeed_ftps = 0.0f;
  return 0;
}
static int size_read_battery_v(void *ctx, float *battery_v) {
  (void)ctx;
  *battery_v = 0.0f;
  return 0;
}
static volatile uint32_t backup_words[HA_RETAINED_WORDS];
static int size_read_retained(void *ctx, uint32_t words[HA_RETAINED_WORDS]) {
  uint32_t i;
  (void)ctx;
  for (i = 0u; i < HA_RETAINED_WORDS; ++i) {
    words[i] = backup_words[i];
  }
  return 1;
}
static void size_write_retained(void *ctx, const uint32_t words[HA_RETAINED_WORDS]) {
  uint32_t i;
  (void)ctx;
  for (i = 0u; i < HA_RETAINED_WORDS; ++i) {
    backup_words[i] = words[i];
  }
}

static HaApp app;

int main(void) {
  static const HaBoard board = {
      .ctx = NULL,
      .micros = size_micros,
      .write_servos = size_write_servos,
      .read_rc = size_read_rc,
      .read_airspeed_ftps = size_read_airspeed_ftps,
      .read_battery_v = size_read_battery_v,
      .set_hp_reset = null_set_hp_reset,
      .set_leds = null_set_leds,
      .kick_watchdog = null_kick_watchdog,
      .read_retained = size_read_retained,
      .write_retained = size_write_retained,
  };
  static HaIns ins;
  HaHpCommand cmd = {0};
  uint32_t i;
  ha_app_init(&app, &ha_aircraft_config);
  ha_ins_init(&ins);
  ha_app_restore(&app, &board, &ins);
  for (i = 0u; i < 3u; ++i) {
    fake_clock_us += 10000u;
    cmd.seq = i;
    cmd.crc32 = ha_hp_command_compute_crc(&cmd);
    ha_inputs_put_hp_command(&app.inputs, &cmd, fake_clock_us);
    ha_app_put_operator(&app, HA_OP_NONE, i);
    ha_app_period(&app, &board);
  }
  return (int)app.outputs.controller;
}
