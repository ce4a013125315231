/* Frama-C EVA analysis driver for the HA core (arduino_ha/src/core). Not compiled into anything:
 * make verify-ha-eva (tools/eva.sh) hands it to frama-c together with every .c of the core.
 *
 * Each period it draws every input from the whole range of its type and calls the core exactly
 * as the firmware does, through ha_app_period (the board functions below return unknown values)
 * and directly through ha_core_step. Two input modes, the cases arduino_ha/make.mk declares:
 *   default            every float input any finite value in [-FLT_MAX, FLT_MAX], every integer
 *                      any value of its type; EVA's default -warn-special-float non-finite then
 *                      raises an alarm for any operation in the core that could produce inf/NaN
 *                      (overflow of huge inputs, division by zero);
 *   HA_EVA_ANY_BITS    every input byte unknown (floats include NaN, +/-inf, denormals), analysed
 *                      with -warn-special-float none: the assertions below then prove that no
 *                      NaN or inf, and nothing outside S_u, ever reaches the servos.
 * HA_EVA_STEPS periods are unrolled (precise); HA_EVA_STEPS 0 instead loops an unknown number of
 * times, so the result holds after any number of periods. */
#include <float.h>
#include <stddef.h>
#include <stdint.h>

#include "__fc_builtin.h"
#include "eva_board.h"
#include "geo_wgs84.h"
#include "ha_aircraft.h"
#include "ha_app.h"
#include "ha_core.h"
#include "ha_ins.h"

#ifndef HA_EVA_STEPS
#define HA_EVA_STEPS 4
#endif

static void any_hp_command(HaHpCommand *cmd) {
  cmd->seq = any_u32();
  cmd->stamp_sec = any_u32();
  cmd->stamp_nsec = any_u32();
  cmd->throttle = any_float();
  cmd->elevator_deg = any_float();
  cmd->aileron_deg = any_float();
  cmd->rudder_deg = any_float();
  cmd->alpha_est_deg = any_float();
  cmd->beta_est_deg = any_float();
  cmd->estimator_converged = any_u8();
  cmd->sensor_links_healthy = any_u8();
  cmd->crc32 = any_u32();
}

/* Everything the link and the INS side may have written between two periods. */
static void any_link_inputs(HaInputs *in) {
  HaHpCommand cmd;
  in->roll_deg = any_float();
  in->pitch_deg = any_float();
  in->heading_deg = any_float();
  in->p_deg_s = any_float();
  in->q_deg_s = any_float();
  in->r_deg_s = any_float();
  in->altitude_agl_ft = any_float();
  in->north_ft = any_float();
  in->east_ft = any_float();
  in->groundspeed_ftps = any_float();
  in->vel_north_ftps = any_float();
  in->vel_east_ftps = any_float();
  in->climb_ftps = any_float();
  in->altitude_msl_ft = any_float();
  in->on_ground = any_u8();
  in->state_valid = any_u8();
  in->home_unknown = any_u8();
  in->state_rx_us = any_u32();
  if (Frama_C_nondet(0, 1)) {
    any_hp_command(&cmd);
    ha_inputs_put_hp_command(in, &cmd, any_u32());
  } else {
    /* A link that corrupts its own bookkeeping must not matter either. */
    any_hp_command(&in->hp_cmd);
    in->hp_cmd_count = any_u32();
    in->hp_cmd_rx_us = any_u32();
  }
  in->operator_command = any_u8();
}

/* The operator's requests as the link queues them, or a queue whose bookkeeping is anything. */
static void any_operator_requests(HaApp *a) {
  HaOperatorQueue *q = &a->requests;
  if (Frama_C_nondet(0, 1)) {
    ha_app_put_operator(a, any_u8(), any_u32());
  } else {
    uint32_t k;
    for (k = 0u; k < HA_OPERATOR_QUEUE_LEN; ++k) {
      q->queue[k].command = any_u8();
      q->queue[k].request_id = any_u32();
    }
    q->count = any_u32();
  }
}

static void any_inputs(HaInputs *in) {
  any_link_inputs(in);
  in->airspeed_ftps = any_float();
  any_rc(&in->rc);
}

/* The decision reported to the HP side is always one of the defined values. */
static void check_decision(const HaOutputs *out) {
  const uint8_t leds = ha_app_leds(out);
  /*@ assert controller_defined: out->controller <= HA_CONTROLLER_MANUAL; */
  /*@ assert reasons_defined: (out->reasons & ~(uint32_t)0x7FFFu) == 0; */
  /*@ assert leds_defined: (leds & ~(uint8_t)0x0Fu) == 0; */
}

/* One VN-200 solution with every field unknown, as the Due's seam hands it to the adapter. */
static void any_ins_sample(HaInsSample *s) {
  size_t i;
  s->has = any_u8();
  for (i = 0u; i < 3u; ++i) {
    s->ypr_deg[i] = any_float();
    s->angular_rate_radps[i] = any_float();
    s->vel_ned_mps[i] = any_float();
    s->accel_mps2[i] = any_float();
  }
  s->lat_deg = any_double();
  s->lon_deg = any_double();
  s->alt_m = any_double();
  s->ins_status = Frama_C_unsigned_short_interval(0u, 65535u);
  s->gps_fix = any_u8();
}

/* The geodesy module's HP-side uses (vn200 tf, microhard_gs, the GNC): a reference from any
 * input, then points inside its documented domain (latitude, longitude, height in range; north,
 * east, up within 1000 km). */
static void any_geodesy_use(void) {
  GeoRef ref;
  double neu[3];
  double lat;
  double lon;
  double alt;
  /* A valid reference first, as every caller holds one (home) before it converts: EVA joins
   * geo_ref_init's two exits, so the refused one must leave a reference behind. */
  if (!geo_ref_init(&ref, 0.0, 0.0, 0.0)) {
    return;
  }
  (void)geo_ref_init(&ref, any_double(), any_double(), any_double());
  geo_to_neu_ft(&ref, Frama_C_double_interval(-90.0, 90.0), Frama_C_double_interval(-180.0, 180.0),
                Frama_C_double_interval(-1.0e4, 1.0e5), neu);
  neu[0] = Frama_C_double_interval(-1.0e6, 1.0e6);
  neu[1] = Frama_C_double_interval(-1.0e6, 1.0e6);
  neu[2] = Frama_C_double_interval(-1.0e6, 1.0e6);
  geo_from_neu_ft(&ref, neu, &lat, &lon, &alt);
}

static HaApp app;
static HaCore core;
static HaIns ins;
static HaInputs inputs;
static HaOutputs outputs;

static void one_period(const HaBoard *board) {
  HaInsSample sample;
  /* Through the app exactly as the firmware runs it: the link's fields unknown, then (or not) an
   * INS solution through the adapter, as the Due's seam applies it ... */
  any_link_inputs(&app.inputs);
  any_operator_requests(&app);
  if (Frama_C_nondet(0, 1)) {
    any_ins_sample(&sample);
    (void)ha_ins_update(&ins, &ha_aircraft_config, &sample, any_u8(), any_u32(), &app.inputs);
  }
  if (Frama_C_nondet(0, 1)) { /* an operator's SET_HOME, any position, any verdict */
    (void)ha_ins_set_home(&ins, any_u8(), any_u8(), any_double(), any_double(), any_double());
  }
  ha_app_period(&app, board);
  check_servo_command(&app.outputs.surfaces);
  check_decision(&app.outputs);
  /* ... and the core alone, with every input (incl. its own sensor fields) unknown. */
  any_inputs(&inputs);
  ha_core_step(&core, &inputs, any_u32(), &outputs);
  check_servo_command(&outputs.surfaces);
  check_decision(&outputs);
  any_geodesy_use();
}

int main(void) {
  static const HaBoard board = {.ctx = NULL, HA_EVA_BOARD_ENTRIES};
  ha_app_init(&app, &ha_aircraft_config);
  ha_core_init(&core, &ha_aircraft_config);
  ha_ins_init(&ins);
  /* After any reset: whatever the backup registers hold comes back through the record's checks. */
  ha_app_restore(&app, &board, &ins);
  /* The first period starts from init with unknown inputs ... */
#if HA_EVA_STEPS > 0
  {
    int i;
    for (i = 0; i < HA_EVA_STEPS; ++i) {
      one_period(&board);
    }
  }
#else
  /* ... and this loop runs an unknown number of periods: EVA's loop invariant covers them all. */
  while (Frama_C_nondet(0, 1)) {
    one_period(&board);
  }
#endif
  return 0;
}
