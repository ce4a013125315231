/* For the Frama-C EVA drivers (eva_main.c, eva_firmware_main.c), not compiled into anything: a
 * board whose every reading is unknown, and what must hold for anything it is asked to put on a
 * servo. HA_EVA_ANY_BITS: every float any bit pattern (NaN, inf, denormals), else any finite value.
 */
#ifndef HA_EVA_BOARD_H
#define HA_EVA_BOARD_H

#include <float.h>
#include <stddef.h>
#include <stdint.h>

#include "__fc_builtin.h"
#include "ha_aircraft.h"
#include "ha_board.h"
#include "ha_surfaces.h"
#include "null_outputs.h"

/* any_float() and any_double(): one rule for "any value" of both types, in either mode. */
#ifdef HA_EVA_ANY_BITS
#define EVA_ANY_VALUE(type, finite_interval)    \
  static type any_##type(void) {                \
    type v;                                     \
    Frama_C_make_unknown((char *)&v, sizeof v); \
    return v;                                   \
  }
#else
#define EVA_ANY_VALUE(type, finite_interval) \
  static type any_##type(void) { return (finite_interval); }
#endif
EVA_ANY_VALUE(float, Frama_C_float_interval(-FLT_MAX, FLT_MAX))
EVA_ANY_VALUE(double, Frama_C_double_interval(-DBL_MAX, DBL_MAX))

static uint32_t any_u32(void) { return Frama_C_unsigned_int_interval(0u, UINT32_MAX); }

static uint8_t any_u8(void) { return (uint8_t)Frama_C_interval(0, 255); }

static void any_rc(HaRcInputs *rc) {
  size_t i;
  for (i = 0u; i < (size_t)HA_RC_CHANNELS; ++i) {
    rc->pulse_us[i] = Frama_C_unsigned_short_interval(0u, 65535u);
  }
  rc->valid = any_u8();
}

/* What must hold for anything that reaches a servo: finite and inside the actuator box S_u is
 * built from (the configuration's limits). */
static void check_servo_command(const HaSurfaces *s) {
  const HaAircraftConfig *cfg = &ha_aircraft_config;
  /*@ assert servo_throttle_finite: \is_finite(s->throttle); */
  /*@ assert servo_elevator_finite: \is_finite(s->elevator_deg); */
  /*@ assert servo_aileron_finite: \is_finite(s->aileron_deg); */
  /*@ assert servo_rudder_finite: \is_finite(s->rudder_deg); */
  /*@ assert servo_elevator_in_su:
        -cfg->elevator_limit_deg <= s->elevator_deg <= cfg->elevator_limit_deg; */
  /*@ assert servo_aileron_in_su:
        -cfg->aileron_limit_deg <= s->aileron_deg <= cfg->aileron_limit_deg; */
  /*@ assert servo_rudder_in_su:
        -cfg->rudder_limit_deg <= s->rudder_deg <= cfg->rudder_limit_deg; */
  /*@ assert servo_throttle_in_su: cfg->throttle_min <= s->throttle <= cfg->throttle_max; */
  {
    uint16_t pulses_us[HA_U_DIM];
    ha_surfaces_to_pulses_us(cfg, s, pulses_us);
  }
}

/* ---- A board whose every reading is unknown. ---- */
static uint32_t eva_micros(void *ctx) {
  (void)ctx;
  return any_u32();
}
static void eva_write_servos(void *ctx, const HaSurfaces *surfaces) {
  (void)ctx;
  check_servo_command(surfaces);
}
static void eva_read_rc(void *ctx, HaRcInputs *rc) {
  (void)ctx;
  any_rc(rc);
}
/* A reading may fail in either mode: ha_app then passes it on as -1, which the core's range checks
 * reject. */
static int any_reading_ok(void) { return Frama_C_nondet(0, 1); }
static int eva_read_airspeed_ftps(void *ctx, float *airspeed_ftps) {
  (void)ctx;
  *airspeed_ftps = any_float();
  return any_reading_ok();
}
static int eva_read_battery_v(void *ctx, float *battery_v) {
  (void)ctx;
  *battery_v = any_float();
  return any_reading_ok();
}
/* Backup registers holding anything at all: a power-up's random bits, a torn write. */
static int eva_read_retained(void *ctx, uint32_t words[HA_RETAINED_WORDS]) {
  uint32_t i;
  (void)ctx;
  for (i = 0u; i < HA_RETAINED_WORDS; ++i) {
    words[i] = any_u32();
  }
  return Frama_C_nondet(0, 1);
}
static void eva_write_retained(void *ctx, const uint32_t words[HA_RETAINED_WORDS]) {
  (void)ctx;
  (void)words;
}

/* The Board's entries above, for a designated initializer. */
#define HA_EVA_BOARD_ENTRIES                                                          \
  .micros = eva_micros, .write_servos = eva_write_servos, .read_rc = eva_read_rc,     \
  .read_airspeed_ftps = eva_read_airspeed_ftps, .read_battery_v = eva_read_battery_v, \
  .set_hp_reset = null_set_hp_reset, .set_leds = null_set_leds,                       \
  .kick_watchdog = null_kick_watchdog, .read_retained = eva_read_retained,            \
  .write_retained = eva_write_retained

#endif /* HA_EVA_BOARD_H */
