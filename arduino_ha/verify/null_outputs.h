/* The Board outputs that go nowhere, for the drivers that run the core without a board: the EVA
 * board (eva_board.h) and the Cortex-M3 size program (size_main.c). The HP reset line, the LEDs
 * and the watchdog: what the core asks of them is its own business there. */
#ifndef HA_NULL_OUTPUTS_H
#define HA_NULL_OUTPUTS_H

#include <stdint.h>

static void null_set_hp_reset(void *ctx, int asserted) {
  (void)ctx;
  (void)asserted;
}
static void null_set_leds(void *ctx, uint8_t leds) {
  (void)ctx;
  (void)leds;
}
static void null_kick_watchdog(void *ctx) { (void)ctx; }

#endif /* HA_NULL_OUTPUTS_H */
