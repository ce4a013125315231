/* What both Due boards share (the flight board, due_board.h, and the HIL board, due_hil_board.h):
 * the two byte ports the firmware loop reads (the HP link on the USB port DUE_HP_LINK_PORT
 * chooses, the VN-200 on Serial1), the status LEDs, the SAM3X watchdog and its backup registers.
 * One copy, so that the HIL build flies the flight build's ports and chip, not a lookalike. */
#ifndef DUE_COMMON_H
#define DUE_COMMON_H

#include <stdint.h>

#include "../firmware/ha_board.h"

/* Pins (HP reset low, LEDs off) and both serial ports started. */
void due_common_begin(void);

/* Fills the board's micros() (the SAM3X's own clock), HP link and INS ports, set_leds,
 * kick_watchdog and the retained words. */
void due_common_board(HaBoard *board);

#endif /* DUE_COMMON_H */
