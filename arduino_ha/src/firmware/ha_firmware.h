/* The HA firmware's loop, one for every board: the Due (board_due/), the host SIL (sil/ha_sil.c)
 * and the host tests' fake board (test/fake_board.cpp) run this and add only their Board
 * (ha_board.h: pins, clock, retained words and the two byte ports).
 *
 * What it does, so no board does it again:
 *  - the period schedule: one ha_app_period (the core's step, servos, reset line, LEDs, retained
 *    words, the watchdog kick) when its time has come; a loop more than a period behind starts
 *    the schedule afresh from now instead of running a burst of catch-up periods. Paced by the
 *    command (HaFirmwareOptions.pace_by_command), a period runs when a new HP command has come
 *    and at least 3/4 of a period has passed since the last, else on the clock: 5/4 of a period
 *    after a period with a command, and after one without on the grid a free clock keeps
 *    (hil/README.md, "Sensor to servo");
 *  - the HP link: bytes from the board's HP port into the rosserial device end (link/ha_link.h),
 *    its replies out through the same port, its time sync kept going;
 *  - the INS feed: bytes from the board's INS port into the VN-200 rule (vn200/ha_vn200_feed.h),
 *    which hands each solution to the core's INS adapter;
 *  - operator routing: SET_HOME to the INS adapter (judged on the core's latest on-the-ground
 *    verdict, answered in the host's log), every other request (restart, HP/HA selection) queued
 *    for the core (ha_app_put_operator); HP commands into the core's inputs;
 *  - the reports: DecisionStatus, pwm and home each period (link/ha_link_report.h), a log when
 *    the host negotiated the link, and the link's drop counters whenever it dropped something new.
 * C99, no heap, no recursion, every loop bounded, time from the board's clock. */
#ifndef HA_FIRMWARE_H
#define HA_FIRMWARE_H

#include <stddef.h>
#include <stdint.h>

#include "../generated/ha_config.h"
#include "../link/ha_link.h"
#include "../vn200/ha_vn200_feed.h"
#include "ha_app.h"
#include "ha_board.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Bytes one read takes from a port: at 250000 baud a Due loop pass (tens of microseconds) finds
 * far fewer waiting, and 64 bytes keep the read buffer off the core's deepest stack. */
#define HA_FW_READ_CHUNK 64u

/* Sees each HP command as it is handed to the core (the SIL's latency log and its counts). */
typedef void (*HaFirmwareCommandTap)(void *ctx, const HaHpCommand *cmd, uint32_t arrival_us);

/* What a board chooses; kept across ha_firmware_start (a reset keeps the board's settings). */
typedef struct {
  /* Logged to the host each time it negotiates the link (e.g. "HA SIL link up"); NULL: none. */
  const char *link_up_text;
  /* A parameter asked of the host at each link-up, its answer logged back; NULL: none. */
  const char *probe_param;
  /* The schedule's period; 0: the aircraft's period_us. */
  uint32_t period_us;
  /* Reads of up to HA_FW_READ_CHUNK bytes per port per loop pass; 0 counts as 1. */
  uint32_t reads_per_pass;
  HaFirmwareCommandTap command_tap; /* NULL: none */
  void *tap_ctx;
  /* Nonzero: the period runs on the HP command's arrival (ha_firmware_loop; a board on its own
   * clock: the Due, the SIL and QEMU in real time). 0: every period_us on the clock. */
  int pace_by_command;
} HaFirmwareOptions;

typedef struct {
  const HaAircraftConfig *cfg;
  const HaBoard *board;
  HaFirmwareOptions opts;
  HaApp app;
  HaLink link;
  HaVn200Feed ins;
  uint32_t period_us;
  uint32_t next_period_us;
  uint32_t period_at_us;       /* the loop's time of the last period it ran */
  uint32_t commands_at_period; /* the link's command count at that period */
  int commanded;               /* that period had a new command */
  uint32_t negotiations_seen;  /* the link's topic requests already answered with link_up_text */
  uint32_t errors_logged;      /* the sum of the drop counters last reported */
  uint32_t errors_logged_us;   /* when */
} HaFirmware;

/* Power-up or a reset (what the Due's setup() does): the core, the INS feed and the link afresh,
 * then what the board's retained words kept taken back (ha_app_restore). The first period runs
 * at the first loop pass. board and cfg must outlive fw; opts is copied (NULL: all defaults). */
void ha_firmware_start(HaFirmware *fw, const HaBoard *board, const HaAircraftConfig *cfg,
                       const HaFirmwareOptions *opts);

/* One pass of the main loop, as often as the board can call it: ha_firmware_receive, then
 * ha_firmware_service, then ha_firmware_period if its time has come. Returns 1 when a period ran
 * (its time in fw->period_at_us), else 0. */
int ha_firmware_loop(HaFirmware *fw);

/* The pieces of a pass, for a board whose schedule is not its own (the SIL in lockstep with a
 * simulator). Reads each port up to `reads` times (the HP port first), stopping at a read that
 * finds fewer than HA_FW_READ_CHUNK bytes, and applies what came at now_us. Returns the bytes
 * taken. now_us must never run backwards across calls (it may wrap). */
size_t ha_firmware_receive(HaFirmware *fw, uint32_t now_us, uint32_t reads);
/* Keeps the link's time sync going, logs a link-up and the link's new drop counters. */
void ha_firmware_service(HaFirmware *fw, uint32_t now_us);
/* One period (ha_app_period) and its reports, stamped now_us. */
void ha_firmware_period(HaFirmware *fw, uint32_t now_us);

/* Everything the link has dropped so far (decoder and session counters). */
uint32_t ha_firmware_link_errors(const HaLink *link);

#ifdef __cplusplus
}
#endif

#endif /* HA_FIRMWARE_H */
