/* One period of the HA computer around the core: read the Board, step the core, write the
 * Board. The sketch and the host tests call ha_app_period() at the control rate; the link writes
 * HP commands and INS state into app->inputs and operator requests into app's queue between
 * periods (ha_inputs_put_hp_command, ha_app_put_operator) and reads app->outputs to send
 * DecisionStatus. */
#ifndef HA_APP_H
#define HA_APP_H

#include "../core/ha_core.h"
#include "../core/ha_ins.h"
#include "ha_board.h"
#include "ha_retained.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Requests waiting for their turn, at most (a power of two: the index is a mask). The ground
 * station sends queued requests back to back; the core takes one a period. */
#define HA_OPERATOR_QUEUE_LEN 4u

typedef struct {
  uint8_t command; /* HA_OP_* */
  uint32_t request_id;
} HaOperatorRequest;

/* The operator's requests between the link and the core: the k-th since boot (from 0) in
 * queue[k % HA_OPERATOR_QUEUE_LEN], handed to the core one a period, oldest first. One
 * overwritten before its turn is counted lost, never executed nor acknowledged. A repeat of the
 * request executed last (same request_id and command: a sender that heard no answer, a link that
 * delivered it twice) is answered again with its first answer and not handed over again, so one
 * RESTART_HP delivered three times restarts the HP once. request_id 0 is an id like any other. */
typedef struct {
  HaOperatorRequest queue[HA_OPERATOR_QUEUE_LEN];
  uint32_t count; /* arrived (ha_app_put_operator) */
  uint32_t seen;  /* answered or lost */
  /* The request answered last (one a period at most): ack_count counts every answer, and
   * ack_count + lost equals count once every request had its turn. */
  uint32_t ack_id;
  uint8_t ack_accepted;
  uint32_t ack_count;
  uint32_t lost;
  uint8_t executed; /* some request was handed to the core since boot: last is it */
  HaOperatorRequest last;
  uint8_t last_accepted;
} HaOperatorQueue;

typedef struct {
  HaCore core;
  HaInputs inputs;
  HaOutputs outputs;
  HaOperatorQueue requests;
  /* The board's last battery reading (-1: it failed). No decision uses it, and no message carries
   * it to the HP side yet. */
  float battery_v;
  /* Kept across a reset (ha_app_restore): the INS adapter whose home is kept, whether the board's
   * retained words are kept up to date, and what they hold. */
  HaIns *ins;
  uint8_t retain;
  HaRetained kept;
} HaApp;

void ha_app_init(HaApp *app, const HaAircraftConfig *cfg);

/* Once after ha_app_init and the INS adapter's init, before the first period: takes back what the
 * board's retained words hold from before a reset (ha_retained.h: the airborne latch, the restart
 * cap's latch, the operator's HA selection, and home into *ins), and from then on keeps them up to
 * date at the end of every period in which one of those changed. ins may be NULL (no home kept).
 * A board without retained words (read_retained NULL or returning 0) starts as from power-up. */
void ha_app_restore(HaApp *app, const HaBoard *board, HaIns *ins);

/* Reads clock, RC and airspeed from the board into app->inputs (the battery into app), runs
 * ha_core_step, then writes servos, the HP reset line and LEDs, the retained words when what they
 * keep changed (after ha_app_restore), and kicks the watchdog. A failed airspeed or battery reading
 * is passed on as -1, which the core's range checks reject. */
void ha_app_period(HaApp *app, const HaBoard *board);

/* Records an HP command the link delivered, received at now_us (increments hp_cmd_count). */
void ha_inputs_put_hp_command(HaInputs *in, const HaHpCommand *cmd, uint32_t now_us);

/* Queues an operator request the link delivered; ha_app_period hands it to the core in its turn
 * (SET_HOME is the INS adapter's: never queued here). */
void ha_app_put_operator(HaApp *app, uint8_t command, uint32_t request_id);

/* The status LEDs (HA_LED_*) for the core's outputs: who drives the servos (the HA's lamp for
 * the HA, recovering and latched), and FAULT while any check fails. */
uint8_t ha_app_leds(const HaOutputs *out);

#ifdef __cplusplus
}
#endif

#endif /* HA_APP_H */
