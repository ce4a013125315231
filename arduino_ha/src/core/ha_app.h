/* One period of the HA computer around the core: read the Board, step the core, write the
 * Board. The sketch and the host tests call ha_app_period() at the control rate; the link writes
 * HP commands, INS state and operator requests into app->inputs between periods (with
 * ha_inputs_put_hp_command / ha_inputs_put_operator) and reads app->outputs to send
 * DecisionStatus. */
#ifndef HA_APP_H
#define HA_APP_H

#include "ha_board.h"
#include "ha_core.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
  HaCore core;
  HaInputs inputs;
  HaOutputs outputs;
} HaApp;

void ha_app_init(HaApp *app, const HaAircraftConfig *cfg);

/* Reads clock, RC, airspeed and battery from the board into app->inputs, runs ha_core_step,
 * then writes servos, the HP reset line and LEDs, and kicks the watchdog. A failed airspeed or
 * battery reading is passed on as -1, which the core's range checks reject. */
void ha_app_period(HaApp *app, const HaBoard *board);

#ifdef __cplusplus
}
#endif

#endif /* HA_APP_H */
