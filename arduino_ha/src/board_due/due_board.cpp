#include "due_board.h"

#include <Arduino.h>
#include <Servo.h>
#include <Wire.h>

#include "../core/ha_core.h"
#include "ams5812.h"
#include "due_config.h"
#include "due_rc_capture.h"

namespace {

/* Indexed by HA_U_* (core/ha_config.h), the order ha_surfaces_to_pulses_us() fills. */
const uint32_t kServoPins[HA_U_DIM] = {DUE_PIN_SERVO_ELEVATOR, DUE_PIN_SERVO_AILERON,
                                       DUE_PIN_SERVO_RUDDER, DUE_PIN_SERVO_THROTTLE};
Servo g_servos[HA_U_DIM];

const uint32_t kLedPins[4] = {DUE_PIN_LED_HP, DUE_PIN_LED_HA, DUE_PIN_LED_MANUAL,
                              DUE_PIN_LED_FAULT};
const uint8_t kLedBits[4] = {HA_LED_HP, HA_LED_HA, HA_LED_MANUAL, HA_LED_FAULT};

#if DUE_HP_LINK_PORT == DUE_HP_LINK_PORT_PROGRAMMING
/* UART0 through the 16U2: its 128-byte receive ring holds 5 ms at 250000 baud (loop() drains it
 * far more often); write() waits out a period's 150-byte burst (0.9 ms) in its transmit ring. */
UARTClass &g_hp_port = Serial;
#elif DUE_HP_LINK_PORT == DUE_HP_LINK_PORT_NATIVE
Serial_ &g_hp_port = SerialUSB;
#else
#error "DUE_HP_LINK_PORT must be DUE_HP_LINK_PORT_PROGRAMMING or _NATIVE (due_config.h)"
#endif

DueBoard *as_due(void *ctx) { return static_cast<DueBoard *>(ctx); }

/* What the port's receive ring holds, up to max_len: never waits for more. The VN-200's port 1 on
 * Serial1 brings about 115 bytes a 10 ms period at 115200 baud. */
template <typename Port>
size_t read_port(Port &port, uint8_t *bytes, size_t max_len) {
  size_t n = 0u;
  while (n < max_len && port.available() > 0) {
    bytes[n++] = static_cast<uint8_t>(port.read());
  }
  return n;
}

size_t hp_read(void *ctx, uint8_t *bytes, size_t max_len) {
  (void)ctx;
  return read_port(g_hp_port, bytes, max_len);
}

void hp_write(void *ctx, const uint8_t *bytes, size_t len) {
  (void)ctx;
  (void)g_hp_port.write(bytes, len);
}

size_t ins_read(void *ctx, uint8_t *bytes, size_t max_len) {
  (void)ctx;
  return read_port(Serial1, bytes, max_len);
}

uint32_t board_micros(void *ctx) {
  (void)ctx;
  return micros();
}

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

void board_set_leds(void *ctx, uint8_t leds) {
  (void)ctx;
  for (uint32_t i = 0u; i < 4u; ++i) {
    digitalWrite(kLedPins[i], (leds & kLedBits[i]) != 0u ? HIGH : LOW);
  }
}

void board_kick_watchdog(void *ctx) {
  (void)ctx;
  watchdogReset();
}

/* The SAM3X8E's eight general-purpose backup registers (SUPC backup domain, datasheet 17/18):
 * kept across watchdog, software and user resets and a brown-out of the core supply, lost when
 * the power goes (the Due has no backup battery on VDDBU). Random at power-up: the record's CRC
 * tells (core/ha_retained.c). */
int board_read_retained(void *ctx, uint32_t words[HA_RETAINED_WORDS]) {
  (void)ctx;
  for (uint32_t i = 0u; i < HA_RETAINED_WORDS; ++i) {
    words[i] = GPBR->SYS_GPBR[i];
  }
  return 1;
}

void board_write_retained(void *ctx, const uint32_t words[HA_RETAINED_WORDS]) {
  (void)ctx;
  for (uint32_t i = 0u; i < HA_RETAINED_WORDS; ++i) {
    GPBR->SYS_GPBR[i] = words[i];
  }
}

}  // namespace

/* Called by the SAM core's init() before setup(). The SAM3X watchdog mode register can be
 * written only once after reset, so this is the one place to enable it; the core's default
 * disables it. A loop that stops completing periods stops kicking, and the chip resets. */
void watchdogSetup(void) { watchdogEnable(DUE_WATCHDOG_TIMEOUT_MS); }

void due_board_begin(DueBoard *due, const HaAircraftConfig *cfg) {
  due->cfg = cfg;
  due->servos_attached = 0u;
  due->airspeed_failures = 0u;
  due->board.ctx = due;
  due->board.micros = board_micros;
  due->board.write_servos = board_write_servos;
  due->board.read_rc = board_read_rc;
  due->board.read_airspeed_ftps = board_read_airspeed_ftps;
  due->board.read_battery_v = board_read_battery_v;
  due->board.set_hp_reset = board_set_hp_reset;
  due->board.set_leds = board_set_leds;
  due->board.kick_watchdog = board_kick_watchdog;
  due->board.read_retained = board_read_retained;
  due->board.write_retained = board_write_retained;
  due->board.hp_link.read = hp_read;
  due->board.hp_link.write = hp_write;
  due->board.ins.read = ins_read;
  due->board.ins.write = nullptr; /* the VN-200's output is configured in its own flash */

  pinMode(DUE_PIN_HP_RESET, OUTPUT);
  digitalWrite(DUE_PIN_HP_RESET, LOW);
  for (uint32_t i = 0u; i < 4u; ++i) {
    pinMode(kLedPins[i], OUTPUT);
    digitalWrite(kLedPins[i], LOW);
  }
  analogReadResolution(DUE_ADC_BITS);
  Wire.begin();
  Wire.setClock(DUE_I2C_CLOCK_HZ);
  due_rc_begin();
  g_hp_port.begin(DUE_HP_LINK_BAUD); /* the native port ignores the rate */
  Serial1.begin(DUE_VN200_BAUD);
}

const HaBoard *due_board_interface(DueBoard *due) { return &due->board; }
