/* The SIL's Board (src/firmware/ha_board.h): what the Due reads from its pins comes from the
 * simulator's latest control record (ha_sil_pins.h), its clock is the host's or the simulator's,
 * its HP link is a pseudo-terminal standing in for the USB cable and its INS port the pty the
 * simulator writes the VN-200's port 1 to. Everything else is the firmware loop's (src/firmware/).
 */
#ifndef HA_SIL_BOARD_H
#define HA_SIL_BOARD_H

#include <signal.h>
#include <stdint.h>

#include "../src/firmware/ha_board.h"
#include "../src/hil/ha_sil_channel.h"
#include "../src/hil/ha_sil_pins.h"

typedef struct {
  HaSilPins pins; /* first: the pins' Board functions take this board's ctx (ha_sil_pins.h) */
  HaBoard iface;
  int master_fd; /* the HP link's pty, -1 while unplugged */
  int slave_fd;  /* held open so the node reopening its end never hangs up ours */
  const char *port_path;
  int vn_fd;         /* the HA's VN-200 port, -1 without --vn200 */
  uint64_t vn_bytes; /* taken from it since the start (a reset of the HA does not clear it) */
  int channel_fd;    /* the simulator's control channel, -1 without --lockstep */
  int sim_clock;     /* 1: micros() is sim_now_us (lockstep) */
  uint32_t sim_now_us;
} SilBoard;

/* No pty, no VN-200 port, no channel yet; the Board's functions set. */
void sil_board_init(SilBoard *b);
/* A fresh pty published under port_path (a symlink, like /dev/ttyACM0); 0 on success. */
int sil_board_plug(SilBoard *b);
/* Closes the pty and removes the symlink: the USB cable pulled. */
void sil_board_unplug(SilBoard *b);
/* Opens the VN-200 pty (raw, 115200 baud), retrying while the simulator starts; 0 on success.
 * stop: gives up early when it becomes nonzero. */
int sil_board_open_vn200(SilBoard *b, const char *path, volatile const sig_atomic_t *stop);

#endif /* HA_SIL_BOARD_H */
