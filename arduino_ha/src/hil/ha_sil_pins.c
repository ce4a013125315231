#include "ha_sil_pins.h"

#include <string.h>

#include "ha_sil_records.h"

static HaSilPins *as_pins(void *ctx) { return (HaSilPins *)ctx; }

static void pins_write_servos(void *ctx, const HaSurfaces *s) {
  (void)ctx;
  (void)s; /* the simulator reads the core's outputs, which is what was written */
}

/* Before the simulator's first record, a healthy receiver in computer-in-command (the firmware
 * runs no period before it in lockstep). */
static void pins_read_rc(void *ctx, HaRcInputs *rc) {
  const HaSilPins *p = as_pins(ctx);
  int k;
  if (p->have_in) {
    for (k = 0; k < HA_RC_CHANNELS; ++k) {
      rc->pulse_us[k] = p->in.rc_pulse_us[k];
    }
    rc->valid = (uint8_t)((p->in.flags & HA_SIL_RC_VALID) != 0u);
    return;
  }
  rc->pulse_us[HA_RC_THROTTLE] = 1100u;
  rc->pulse_us[HA_RC_ELEVATOR] = 1500u;
  rc->pulse_us[HA_RC_AILERON] = 1500u;
  rc->pulse_us[HA_RC_RUDDER] = 1500u;
  rc->pulse_us[HA_RC_PIC] = 1000u; /* computer in command */
  rc->valid = 1u;
}

static int pins_read_airspeed(void *ctx, float *v) {
  const HaSilPins *p = as_pins(ctx);
  if (p->have_in) {
    *v = p->in.airspeed_ftps;
    return (p->in.flags & HA_SIL_AIRSPEED_OK) != 0u;
  }
  *v = 60.0f;
  return p->standalone;
}

static int pins_read_battery(void *ctx, float *v) {
  const HaSilPins *p = as_pins(ctx);
  if (p->have_in) {
    *v = p->in.battery_v;
    return (p->in.flags & HA_SIL_BATTERY_OK) != 0u;
  }
  *v = 12.1f;
  return p->standalone;
}

static void pins_set_hp_reset(void *ctx, int asserted) { as_pins(ctx)->hp_reset = asserted; }

static void pins_set_leds(void *ctx, uint8_t leds) {
  (void)ctx;
  (void)leds; /* the simulator reads the core's outputs */
}

static void pins_kick(void *ctx) { (void)ctx; }

static int pins_read_retained(void *ctx, uint32_t words[HA_RETAINED_WORDS]) {
  memcpy(words, as_pins(ctx)->retained, sizeof as_pins(ctx)->retained);
  return 1;
}

static void pins_write_retained(void *ctx, const uint32_t words[HA_RETAINED_WORDS]) {
  memcpy(as_pins(ctx)->retained, words, sizeof as_pins(ctx)->retained);
}

void ha_sil_pins_board(HaBoard *board) {
  board->write_servos = pins_write_servos;
  board->read_rc = pins_read_rc;
  board->read_airspeed_ftps = pins_read_airspeed;
  board->read_battery_v = pins_read_battery;
  board->set_hp_reset = pins_set_hp_reset;
  board->set_leds = pins_set_leds;
  board->kick_watchdog = pins_kick;
  board->read_retained = pins_read_retained;
  board->write_retained = pins_write_retained;
}

uint32_t ha_sil_pins_take_record(HaSilPins *pins, const uint8_t *bytes, size_t len) {
  HaSilStep st;
  if (!ha_sil_decode_step(bytes, len, &st)) {
    return 0u;
  }
  if (st.magic == HA_SIL_MAGIC_STEP) {
    pins->in = st;
    pins->have_in = 1;
  }
  return st.magic;
}
