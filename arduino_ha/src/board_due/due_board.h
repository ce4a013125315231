/* The Due's implementation of the core's Board interface (firmware/ha_board.h) with the Arduino
 * API: Servo library outputs at 50 Hz, RC capture on pin-change interrupts, the AMS 5812 on I2C,
 * the battery on an ADC pin, the HP reset line, status LEDs, the SAM3X hardware watchdog, the
 * SAM3X's backup registers, and the two byte ports: the HP link on the USB port DUE_HP_LINK_PORT
 * chooses (due_config.h) and the VN-200 on Serial1. Thin on purpose: every decision is the core's,
 * every byte's meaning the firmware loop's (src/firmware/); this file only moves values in and out.
 */
#ifndef DUE_BOARD_H
#define DUE_BOARD_H

#include <stdint.h>

#include "../firmware/ha_board.h"
#include "../generated/ha_config.h"

typedef struct {
  const HaAircraftConfig *cfg;
  uint8_t servos_attached; /* servos are attached at the first command: nothing is driven before */
  uint32_t airspeed_failures; /* I2C reads that returned no plausible reading */
  HaBoard board;
} DueBoard;

/* Configures pins, I2C, ADC, RC capture and both serial ports; leaves the HP out of reset and the
 * servos detached. */
void due_board_begin(DueBoard *due, const HaAircraftConfig *cfg);

/* The Board interface the firmware loop runs over. */
const HaBoard *due_board_interface(DueBoard *due);

#endif /* DUE_BOARD_H */
