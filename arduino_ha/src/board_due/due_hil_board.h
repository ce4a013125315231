/* The Due's HIL build (HA_DUE_HIL=1, due_config.h): a real Due in the simulator's loop. What the
 * flight board reads from its pins (RC incl. the PIC/CIC channel, the AMS5812, the battery) comes
 * from the simulator's latest step record instead (../hil/ha_sil_pins.h, the pins the SIL and the
 * QEMU board read), and what it drives goes back in a reply record after each period: the servos,
 * the HP reset line, the decision, the safety controller's own command (../hil/ha_sil_records.h).
 * The records travel framed as the QEMU board's UART2 takes them (../hil/pil_frame.h: A5 5A,
 * length, record, CRC-32): a frame whose length or CRC fails, or that holds no step, poll or
 * reset record, is counted, dropped and never applied; the count goes back in every reply.
 *
 * They travel on the native USB port (SerialUSB), not on Serial2: no USB-serial adapter to wire,
 * a link without a baud rate (libsam's UDD_Init leaves the SAM3X's USB high-speed capable, 480
 * Mbit/s; full speed, 12 Mbit/s, on a USB 1.1 port) where the 124-byte reply frame every 10 ms
 * (12.4 kB/s) is more than a 115200-baud UART carries (11.5 kB/s) and half of 250000, and USB's own
 * flow control: CDC.cpp's accept() leaves what its 512-byte ring cannot hold in the endpoint and
 * the host waits, where a UART's 128-byte ring drops. What it costs: the native port is the one
 * whose 1200-baud open erases the flash, and a host that keeps it open without reading stalls
 * SerialUSB.write() (libsam's UDD_Send waits for the bank) until the watchdog resets the Due.
 *
 * The clock stays the Due's own (real time only, as the SIL's --realtime): a step record's t_us
 * is not used, a poll record is not answered, a reset record restarts the firmware as a watchdog
 * reset would (RAM afresh, the backup registers kept; the chip itself is not reset, which would
 * drop the native port's enumeration). The HP link stays on Serial (the programming port, the
 * real `arduino` node) and the VN-200 on Serial1, as in flight (due_common.h). The status LEDs
 * light as in flight; the servos and the HP reset pin are not driven: the simulator flies the
 * surfaces from the reply and resets its HP on the reply's flag. */
#ifndef DUE_HIL_BOARD_H
#define DUE_HIL_BOARD_H

#include <stdint.h>

#include "../firmware/ha_board.h"
#include "../firmware/ha_firmware.h"
#include "../generated/ha_config.h"
#include "../hil/ha_sil_pins.h"
#include "../hil/pil_frame.h"

typedef struct {
  HaSilPins pins; /* first: the pins' Board functions take this board's ctx (ha_sil_pins.h) */
  HaBoard board;
  PilFrameRx records;
  uint32_t records_undecodable; /* framed and checked, but no step, poll or reset record */
  uint32_t commands;            /* HP commands the link delivered since power-up */
  uint32_t tx_dropped;          /* reply bytes SerialUSB did not take (no host has it open) */
} DueHilBoard;

/* What the records taken in one pass asked for. */
typedef enum { DUE_HIL_NOTHING = 0, DUE_HIL_RESET = 1 } DueHilRequest;

/* Pins, both serial ports and the native USB port started; no record yet, so nothing reads good
 * (ha_sil_pins.h). */
void due_hil_board_begin(DueHilBoard *hil);

/* The Board interface the firmware loop runs over. */
const HaBoard *due_hil_board_interface(DueHilBoard *hil);

/* The board's counts of HP commands, for HaFirmwareOptions (command_tap, tap_ctx = hil). */
void due_hil_board_count_command(void *ctx, const HaHpCommand *cmd, uint32_t arrival_us);

/* Takes what the native USB port holds (a bounded number of bytes a pass): each good step record
 * becomes the pins' inputs. Stops at a reset record and returns DUE_HIL_RESET (the caller restarts
 * the firmware; the bytes behind it wait for the next pass). */
DueHilRequest due_hil_board_take_records(DueHilBoard *hil);

/* The reply frame of the period fw just ran (its time fw->period_at_us), onto the native USB
 * port; pass_us: how long that loop pass took (micros()), the trailer's period_ticks. */
void due_hil_board_reply(DueHilBoard *hil, const HaFirmware *fw, uint32_t pass_us);

#endif /* DUE_HIL_BOARD_H */
