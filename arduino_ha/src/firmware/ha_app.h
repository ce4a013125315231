/* One period of the HA computer around the core: read the Board, step the core, write the
 * Board. The sketch and the host tests call ha_app_period() at the control rate; the link writes
 * HP commands, INS state and operator requests into app->inputs between periods (with
 * ha_inputs_put_hp_command / ha_inputs_put_operator) and reads app->outputs to send
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

typedef struct {
  HaCore core;
  HaInputs inputs;
  HaOutputs outputs;
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

/* Reads clock, RC, airspeed and battery from the board into app->inputs, runs ha_core_step,
 * then writes servos, the HP reset line and LEDs, the retained words when what they keep changed
 * (after ha_app_restore), and kicks the watchdog. A failed airspeed or battery reading is passed
 * on as -1, which the core's range checks reject. */
void ha_app_period(HaApp *app, const HaBoard *board);

/* The status LEDs (HA_LED_*) for the core's outputs: who drives the servos (the HA's lamp for
 * the HA, recovering and latched), and FAULT while any check fails. */
uint8_t ha_app_leds(const HaOutputs *out);

#ifdef __cplusplus
}
#endif

#endif /* HA_APP_H */
