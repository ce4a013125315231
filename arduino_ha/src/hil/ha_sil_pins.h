/* The Due's pins in a simulator's loop: what the Due's board layer reads from the receiver, the
 * AMS5812 and the battery divider comes from the simulator's latest step record
 * (ha_sil_channel.h); the HP reset line, the LEDs and the servos go nowhere but the reply (which
 * reads the core's outputs); the backup registers are RAM kept across a reset record. The host
 * SIL (ha_sil_board.c) and the QEMU board (../pil/pil_main.c) share it. C99, no heap. */
#ifndef HA_SIL_PINS_H
#define HA_SIL_PINS_H

#include <stddef.h>
#include <stdint.h>

#include "../firmware/ha_board.h"
#include "ha_sil_channel.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
  HaSilStep in; /* the latest step record */
  int have_in;
  /* 1: no simulator at all (ha_sil without --lockstep): a 60 ft/s pitot and a 12.1 V battery
   * read good. 0: nothing reads good before the simulator's first step record, since a made-up
   * airspeed would latch airborne on the ground. */
  int standalone;
  int hp_reset;
  uint32_t retained[HA_RETAINED_WORDS];
} HaSilPins;

/* Fills every Board function but micros() and the two byte ports. The board's ctx must point to
 * a struct whose first member is the HaSilPins (C's first-member rule makes the cast exact). */
void ha_sil_pins_board(HaBoard *board);

/* A control record as a board in real time takes it: a step record's inputs become the pins'.
 * Returns the record's magic (HA_SIL_MAGIC_STEP, _POLL or _RESET: the caller restarts the
 * firmware on a reset), or 0 for bytes that are no record, which the caller counts. */
uint32_t ha_sil_pins_take_record(HaSilPins *pins, const uint8_t *bytes, size_t len);

#ifdef __cplusplus
}
#endif

#endif /* HA_SIL_PINS_H */
