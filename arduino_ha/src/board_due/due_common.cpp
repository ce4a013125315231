#include "due_common.h"

#include <Arduino.h>

#include "due_config.h"

namespace {

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

uint32_t board_micros(void *ctx) {
  (void)ctx;
  return micros();
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

void set_leds(void *ctx, uint8_t leds) {
  (void)ctx;
  for (uint32_t i = 0u; i < 4u; ++i) {
    digitalWrite(kLedPins[i], (leds & kLedBits[i]) != 0u ? HIGH : LOW);
  }
}

void kick_watchdog(void *ctx) {
  (void)ctx;
  watchdogReset();
}

/* The SAM3X8E's eight general-purpose backup registers (SUPC backup domain, datasheet 17/18):
 * kept across watchdog, software and user resets and a brown-out of the core supply, lost when
 * the power goes (the Due has no backup battery on VDDBU). Random at power-up: the record's CRC
 * tells (firmware/ha_retained.c). */
int read_retained(void *ctx, uint32_t words[HA_RETAINED_WORDS]) {
  (void)ctx;
  for (uint32_t i = 0u; i < HA_RETAINED_WORDS; ++i) {
    words[i] = GPBR->SYS_GPBR[i];
  }
  return 1;
}

void write_retained(void *ctx, const uint32_t words[HA_RETAINED_WORDS]) {
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

void due_common_begin(void) {
  pinMode(DUE_PIN_HP_RESET, OUTPUT);
  digitalWrite(DUE_PIN_HP_RESET, LOW);
  for (uint32_t i = 0u; i < 4u; ++i) {
    pinMode(kLedPins[i], OUTPUT);
    digitalWrite(kLedPins[i], LOW);
  }
  g_hp_port.begin(DUE_HP_LINK_BAUD); /* the native port ignores the rate */
  Serial1.begin(DUE_VN200_BAUD);
}

void due_common_board(HaBoard *board) {
  board->micros = board_micros;
  board->set_leds = set_leds;
  board->kick_watchdog = kick_watchdog;
  board->read_retained = read_retained;
  board->write_retained = write_retained;
  board->hp_link.read = hp_read;
  board->hp_link.write = hp_write;
  board->ins.read = ins_read;
  board->ins.write = nullptr; /* the VN-200's output is configured in its own flash */
}
