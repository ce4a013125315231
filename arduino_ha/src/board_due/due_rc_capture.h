/* RC receiver capture on the Due: one pin-change interrupt per channel timestamps both edges
 * with micros(); the high time is the pulse width. The loop copies the latest widths out with
 * interrupts briefly disabled. */
#ifndef DUE_RC_CAPTURE_H
#define DUE_RC_CAPTURE_H

#include <stdint.h>

#include "../core/ha_types.h"

void due_rc_begin(void);

/* Latest widths; rc->valid = 1 only if every channel, the PIC/CIC switch included, delivered a
 * plausible pulse within the last DUE_RC_TIMEOUT_US. */
void due_rc_read(HaRcInputs *rc);

/* Edges that did not make a plausible pulse (noise, a receiver glitch): counted and dropped. */
uint32_t due_rc_glitches(void);

#endif /* DUE_RC_CAPTURE_H */
