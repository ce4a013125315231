#include "due_board.h"

#include "due_config.h"
#if !HA_DUE_HIL /* the HIL build flies due_hil_board.cpp instead */

#include <Arduino.h>
#include <Servo.h>
#include <Wire.h>

#include "../core/ha_core.h"
#include "ams5812.h"
#include "due_common.h"
#include "due_config.h"
#include "due_rc_capture.h"

namespace {

/* Indexed by HA_U_* (generated/ha_config.h), the order ha_surfaces_to_pulses_us() fills. */
const uint32_t kServoPins[HA_U_DIM] = {DUE_PIN_SERVO_ELEVATOR, DUE_PIN_SERVO_AILERON,
                                       DUE_PIN_SERVO_RUDDER, DUE_PIN_SERVO_THROTTLE};
Servo g_servos[HA_U_DIM];

DueBoard *as_due(void *ctx) { return static_cast<DueBoard *>(ctx); }

void board_write_servos(void *ctx, const HaSurfaces *surfaces) {
  DueBoard *due = as_due(ctx);
  uint16_t pulses_us[HA_U_DIM];
  ha_surfaces_to_pulses_us(due->cfg, surfaces, pulses_us);
  if (due->servos_attached == 0u) {
    /* The pulse range given to attach() is the configured one, so the Servo library itself
     * refuses anything wider even if a bug upstream produced it. */
    for (uint32_t i = 0u; i < static_cast<uint32_t>(HA_U_DIM); ++i) {
      g_servos[i].attach(static_cast<int>(kServoPins[i]),
                         static_cast<int>(due->cfg->servo_pulse_min_us),
                         static_cast<int>(due->cfg->servo_pulse_max_us));
    }
    due->servos_attached = 1u;
  }
  for (uint32_t i = 0u; i < static_cast<uint32_t>(HA_U_DIM); ++i) {
    g_servos[i].writeMicroseconds(static_cast<int>(pulses_us[i]));
  }
}

void board_read_rc(void *ctx, HaRcInputs *rc) {
  (void)ctx;
  due_rc_read(rc);
}

int board_read_airspeed_ftps(void *ctx, float *airspeed_ftps) {
  DueBoard *due = as_due(ctx);
  uint8_t bytes[AMS5812_READ_LEN];
  const uint8_t got = Wire.requestFrom(static_cast<uint8_t>(DUE_AMS5812_I2C_ADDRESS),
                                       static_cast<uint8_t>(AMS5812_READ_LEN));
  if (got != AMS5812_READ_LEN) {
    while (Wire.available() > 0) {
      (void)Wire.read(); /* drop a short answer so the next read starts clean */
    }
    due->airspeed_failures++;
    return 0;
  }
  for (uint32_t i = 0u; i < AMS5812_READ_LEN; ++i) {
    bytes[i] = static_cast<uint8_t>(Wire.read());
  }
  Ams5812Reading reading;
  if (!ams5812_decode(bytes, DUE_AMS5812_P_MIN_PA, DUE_AMS5812_P_MAX_PA, &reading)) {
    due->airspeed_failures++;
    return 0;
  }
  *airspeed_ftps = ams5812_airspeed_ftps(reading.diff_pressure_pa);
  return 1;
}

int board_read_battery_v(void *ctx, float *battery_v) {
  (void)ctx;
  const uint32_t counts = analogRead(DUE_PIN_BATTERY);
  *battery_v = static_cast<float>(counts) * (DUE_ADC_REFERENCE_V / DUE_ADC_FULL_SCALE_COUNTS) *
               DUE_BATTERY_DIVIDER_RATIO;
  return 1;
}

void board_set_hp_reset(void *ctx, int asserted) {
  (void)ctx;
  digitalWrite(DUE_PIN_HP_RESET, asserted ? HIGH : LOW);
}

}  // namespace

void due_board_begin(DueBoard *due, const HaAircraftConfig *cfg) {
  due->cfg = cfg;
  due->servos_attached = 0u;
  due->airspeed_failures = 0u;
  due->board.ctx = due;
  due->board.write_servos = board_write_servos;
  due->board.read_rc = board_read_rc;
  due->board.read_airspeed_ftps = board_read_airspeed_ftps;
  due->board.read_battery_v = board_read_battery_v;
  due->board.set_hp_reset = board_set_hp_reset;
  due_common_board(&due->board);

  due_common_begin();
  analogReadResolution(DUE_ADC_BITS);
  Wire.begin();
  Wire.setClock(DUE_I2C_CLOCK_HZ);
  due_rc_begin();
}

const HaBoard *due_board_interface(DueBoard *due) { return &due->board; }

#endif /* !HA_DUE_HIL */
