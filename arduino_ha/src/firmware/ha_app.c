#include "ha_app.h"

#include <string.h>

#include "../core/ha_num.h"

void ha_app_init(HaApp *app, const HaAircraftConfig *cfg) {
  memset(app, 0, sizeof *app);
  ha_core_init(&app->core, cfg);
  /* Before the first period the HA is in charge and the servos idle. */
  app->outputs.controller = HA_CONTROLLER_HA;
  app->outputs.surfaces.throttle = cfg->throttle_min;
}

uint8_t ha_app_leds(const HaOutputs *out) {
  const uint8_t source = out->controller == HA_CONTROLLER_HP       ? HA_LED_HP
                         : out->controller == HA_CONTROLLER_MANUAL ? HA_LED_MANUAL
                                                                   : HA_LED_HA;
  return (uint8_t)(source | (out->reasons != 0u ? HA_LED_FAULT : 0u));
}

void ha_inputs_put_hp_command(HaInputs *in, const HaHpCommand *cmd, uint32_t now_us) {
  in->hp_cmd = *cmd;
  in->hp_cmd_rx_us = now_us;
  in->hp_cmd_count++;
}

void ha_app_put_operator(HaApp *app, uint8_t command, uint32_t request_id) {
  HaOperatorQueue *q = &app->requests;
  HaOperatorRequest *slot = &q->queue[q->count & (HA_OPERATOR_QUEUE_LEN - 1u)];
  slot->command = command;
  slot->request_id = request_id;
  q->count++;
}

/* This period's request for the core: the oldest waiting, answered now. Returns 0 when none is
 * waiting or it repeats the one executed last (answered with its first answer). */
static int take_operator(HaOperatorQueue *q, HaOperatorRequest *req) {
  const uint32_t waiting = q->count - q->seen;
  if (waiting == 0u) {
    return 0;
  }
  if (waiting > HA_OPERATOR_QUEUE_LEN) { /* overwritten before their turn: never run nor acked */
    q->lost += waiting - HA_OPERATOR_QUEUE_LEN;
    q->seen = q->count - HA_OPERATOR_QUEUE_LEN;
  }
  *req = q->queue[q->seen & (HA_OPERATOR_QUEUE_LEN - 1u)];
  q->seen++;
  q->ack_count++;
  q->ack_id = req->request_id;
  if (q->executed && req->request_id == q->last.request_id && req->command == q->last.command) {
    q->ack_accepted = q->last_accepted;
    return 0;
  }
  return 1;
}

/* A failed reading enters the core as -1: below every valid airspeed (and voltage), so the
 * range checks reject it, without the core ever seeing a NaN it did not make itself. */
static float reading_or_invalid(int ok, float value) { return ok ? value : -1.0f; }

/* The retained record follows the core and the adapter; it is rewritten (and its CRC computed)
 * only in a period where one of the kept values changed, so a steady flight costs a few compares.
 */
static void keep_retained(HaApp *app, const HaBoard *board) {
  HaRetained now;
  uint32_t words[HA_RETAINED_WORDS];
  const HaIns *ins = app->ins;
  const HaRetained *k = &app->kept;
  if (!app->retain || board->write_retained == NULL) {
    return;
  }
  memset(&now, 0, sizeof now);
  now.airborne = app->core.airborne;
  now.restart_latched = app->core.latched;
  now.ground_command = app->core.ground_command;
  if (ins != NULL && ins->home_latched) {
    now.home_latched = 1u;
    now.home_seq = ins->home_seq;
    now.home_lat_deg = ins->home.lat_deg;
    now.home_lon_deg = ins->home.lon_deg;
    now.home_alt_m = ins->home.alt_m;
  }
  if (now.airborne == k->airborne && now.restart_latched == k->restart_latched &&
      now.ground_command == k->ground_command && now.home_latched == k->home_latched &&
      now.home_seq == k->home_seq) {
    return;
  }
  ha_retained_pack(&now, words);
  board->write_retained(board->ctx, words);
  app->kept = now;
}

void ha_app_period(HaApp *app, const HaBoard *board) {
  HaOperatorRequest req = {HA_OP_NONE, 0u}; /* written whole by take_operator when handed */
  const int handed = take_operator(&app->requests, &req);
  float airspeed_ftps = 0.0f;
  float battery_v = 0.0f;
  const uint32_t now_us = board->micros(board->ctx);
  const int airspeed_ok = board->read_airspeed_ftps(board->ctx, &airspeed_ftps);
  const int battery_ok = board->read_battery_v(board->ctx, &battery_v);
  board->read_rc(board->ctx, &app->inputs.rc);
  app->inputs.airspeed_ftps = reading_or_invalid(airspeed_ok, airspeed_ftps);
  app->battery_v = reading_or_invalid(battery_ok, battery_v);
  app->inputs.operator_command = handed ? req.command : (uint8_t)HA_OP_NONE;
  ha_core_step(&app->core, &app->inputs, now_us, &app->outputs);
  if (handed) {
    app->requests.ack_accepted = app->outputs.operator_accepted;
    app->requests.executed = 1u;
    app->requests.last = req;
    app->requests.last_accepted = app->outputs.operator_accepted;
  }
  board->write_servos(board->ctx, &app->outputs.surfaces);
  board->set_hp_reset(board->ctx, app->outputs.hp_reset_asserted);
  board->set_leds(board->ctx, ha_app_leds(&app->outputs));
  keep_retained(app, board);
  board->kick_watchdog(board->ctx);
}

void ha_app_restore(HaApp *app, const HaBoard *board, HaIns *ins) {
  uint32_t words[HA_RETAINED_WORDS];
  HaRetained r;
  app->ins = ins;
  app->retain = 1u;
  memset(&app->kept, 0, sizeof app->kept);
  if (board->read_retained == NULL || !board->read_retained(board->ctx, words) ||
      !ha_retained_unpack(words, &r)) {
    return; /* power-up: on the ground, no home */
  }
  if (r.home_latched && ins != NULL &&
      !ha_ins_restore_home(ins, r.home_lat_deg, r.home_lon_deg, r.home_alt_m, r.home_seq)) {
    r.home_latched = 0u;
  }
  ha_core_restore(&app->core, r.airborne, r.restart_latched, r.ground_command);
  app->kept = r;
}

static uint16_t to_pulse(const HaAircraftConfig *cfg, float value, float lo, float hi) {
  const float span_us = (float)(cfg->servo_pulse_max_us - cfg->servo_pulse_min_us);
  /* Clamp the value first: a NaN then maps to neutral (or idle), not to a full deflection. */
  const float f = (ha_clampf(value, lo, hi) - lo) / (hi - lo);
  /* + 0.5 rounds to nearest; f in [0, 1] keeps the result inside the configured pulse range. */
  return (uint16_t)((float)cfg->servo_pulse_min_us + f * span_us + 0.5f);
}

void ha_surfaces_to_pulses_us(const HaAircraftConfig *cfg, const HaSurfaces *s,
                              uint16_t pulses_us[HA_U_DIM]) {
  pulses_us[HA_U_ELEVATOR_DEG] =
      to_pulse(cfg, s->elevator_deg, -cfg->elevator_limit_deg, cfg->elevator_limit_deg);
  pulses_us[HA_U_AILERON_DEG] =
      to_pulse(cfg, s->aileron_deg, -cfg->aileron_limit_deg, cfg->aileron_limit_deg);
  pulses_us[HA_U_RUDDER_DEG] =
      to_pulse(cfg, s->rudder_deg, -cfg->rudder_limit_deg, cfg->rudder_limit_deg);
  pulses_us[HA_U_THROTTLE] = to_pulse(cfg, s->throttle, cfg->throttle_min, cfg->throttle_max);
}
