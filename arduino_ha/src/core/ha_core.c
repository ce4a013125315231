#include "ha_core.h"

#include <string.h>

#include "ha_airdata.h"
#include "ha_checks.h"
#include "ha_num.h"
#include "ha_policy.h"
#include "ha_safety_ctrl.h"
#include "ha_self_test.h"
#include "ha_surfaces.h"

/* Who produced the surfaces last period (a change starts a rate-limited transition). */
enum { SRC_HA = 0, SRC_HP = 1, SRC_MANUAL = 2, SRC_SELF_TEST = 3 };

void ha_core_init(HaCore *core, const HaAircraftConfig *cfg) {
  memset(core, 0, sizeof *core);
  core->cfg = cfg;
  core->controller = HA_CONTROLLER_HA;
  core->applied.throttle = cfg->throttle_min;
  core->last_source = SRC_HA;
  core->own.state_age_us = UINT32_MAX;
  core->own.airspeed_age_us = UINT32_MAX;
  ha_airdata_init(&core->airdata);
  ha_safety_ctrl_reset(&core->sc);
}

void ha_core_restore(HaCore *core, uint8_t airborne, uint8_t latched, uint8_t ground_command) {
  core->airborne = (uint8_t)(airborne != 0u);
  core->latched = (uint8_t)(latched != 0u);
  core->ground_command = (uint8_t)(ground_command != 0u);
}

/* Period length actually elapsed, bounded: past the no-command timeout everything has timed out
 * anyway, and a bound keeps one late call from driving a huge integrator or slew step. */
static uint32_t period_dt_us(const HaCore *core, uint32_t now_us) {
  const uint32_t dt =
      core->have_step ? ha_elapsed_us(now_us, core->last_step_us) : core->cfg->period_us;
  return dt < core->cfg->no_command_timeout_us ? dt : core->cfg->no_command_timeout_us;
}

/* Arrival bookkeeping: new command, consecutive late periods, repeated sequence number. */
static void track_command(HaCore *core, const HaInputs *in, uint32_t now_us, uint32_t dt_us,
                          HaCmdFacts *f) {
  /* Checked every period, not only on arrival: the checks below judge whatever in->hp_cmd
   * holds now, so its integrity must be judged on the same bytes. */
  const uint8_t intact = (uint8_t)(ha_hp_command_compute_crc(&in->hp_cmd) == in->hp_cmd.crc32);
  if (in->hp_cmd_count != core->seen_cmd_count) {
    core->seen_cmd_count = in->hp_cmd_count;
    core->have_cmd = 1u;
    core->late_periods = 0u;
    core->cmd_age_us = ha_elapsed_us(now_us, in->hp_cmd_rx_us);
    /* Only a frame that passed its CRC says anything about the HP's sequence: a bit flip in
     * seq of a corrupt frame would otherwise make the next good command look replayed. */
    core->frozen = 0u;
    if (intact) {
      /* Ahead of the last good one, modulo 2^32: a repeat is a frozen HP, a step back a stale
       * or replayed command. Forward jumps are lost frames, not faults. */
      const uint32_t advance = in->hp_cmd.seq - core->last_seq;
      core->frozen = (uint8_t)(core->have_seq && (advance == 0u || advance > 0x7FFFFFFFu));
      core->last_seq = in->hp_cmd.seq;
      core->have_seq = 1u;
    }
  } else {
    core->late_periods = ha_add_sat(core->late_periods, 1u);
    core->cmd_age_us = ha_add_sat(core->cmd_age_us, dt_us);
  }
  f->have_cmd = core->have_cmd;
  f->intact = intact;
  f->age_us = core->cmd_age_us;
  f->late_periods = core->late_periods;
  f->frozen = core->frozen;
  f->cmd = &in->hp_cmd;
}

/* The INS state's age restarts with each newly stamped valid state, and otherwise counts up by
 * the elapsed periods, saturating: never recomputed from the wrapping clock. A pitot reading in
 * range restarts the airspeed's age; a failed one (-1 from ha_app) ages the last good one. */
static void track_own_sensors(HaCore *core, const HaInputs *in, uint32_t now_us, uint32_t dt_us) {
  HaOwnSensors *own = &core->own;
  const float max_ftps = core->cfg->max_airspeed_ftps;
  const int read = ha_in_range(in->airspeed_ftps, 0.0f, max_ftps);
  const float ias_ftps = ha_clampf(in->airspeed_ftps, 0.0f, max_ftps);
  int fresh, agrees;
  if (in->state_valid != 0u && in->state_rx_us != core->seen_state_rx_us) {
    core->seen_state_rx_us = in->state_rx_us;
    own->state_age_us = ha_elapsed_us(now_us, in->state_rx_us);
  } else {
    own->state_age_us = ha_add_sat(own->state_age_us, dt_us);
  }
  fresh = own->state_age_us <= core->cfg->state_timeout_us && in->state_valid != 0u;
  /* A reading the INS contradicts, low or high (ha_airdata.c), is a lying sensor (zeroed,
   * blocked, stuck), not a stall: it counts as a failed read, so the last good one holds for
   * airspeed_timeout_s, then NO_HA_STATE; the HA flies on the INS less the wind meanwhile. */
  agrees = ha_airdata_track(&core->airdata, core->cfg, in, fresh, read, ias_ftps, dt_us);
  if (read && agrees) {
    own->airspeed_ftps = ias_ftps;
    own->airspeed_age_us = 0u;
  } else {
    own->airspeed_age_us = ha_add_sat(own->airspeed_age_us, dt_us);
  }
}

/* Airborne from several signals, latched: never decided by height alone, so a low pass or
 * terrain below the launch point keeps the motor and the stall check. At power-up the latch is
 * clear (on the ground until a sign of flight; a reset in flight restores it: ha_app.c), and it
 * holds while the sensors cannot tell: a dead pitot or a lost INS never clears it.
 * On the ground is one rule, for the self-test, the first home and SET_HOME (the INS adapter
 * takes it from HaOutputs.on_ground): the latch clear (no sign of flight now or since the last
 * confirmed landing) and every sensor saying landed now: the pitot alive and below stall, a
 * fresh INS parked and low. The motor runs on the latch alone: it idles until a sign of flight,
 * and keeps running while the sensors cannot tell. */
static void decide_airborne(HaCore *core, uint32_t dt_us, HaStateView *v) {
  if (v->flying_evidence) {
    core->airborne = 1u;
    core->landed_for_us = 0u;
  } else if (v->landed_evidence) {
    core->landed_for_us = ha_add_sat(core->landed_for_us, dt_us);
    if (core->landed_for_us >= core->cfg->landed_confirm_us) {
      core->airborne = 0u;
    }
  } else {
    core->landed_for_us = 0u;
  }
  v->airborne = core->airborne;
  v->on_ground = (uint8_t)(!core->airborne && v->landed_evidence);
  v->parked = (uint8_t)(v->on_ground && v->still && v->altitude_ok);
}

/* Forget restarts older than the window (before the 32-bit clock could wrap onto them). Proved
 * (make prove-ha): what is kept is exactly the history's restarts of the last window, so the cap
 * counts every one of them and none older. */
#ifdef HA_WP
/*@ // The restarts among the first n of t within the window of now.
  @ logic integer ha_recent{L}(uint32_t *t, integer n, integer now, integer window) =
  @   n <= 0 ? 0 : ha_recent(t, n - 1, now, window) + (ha_elapsed(now, t[n - 1]) < window ? 1 : 0);
  @ */
/*@ requires \valid(core) && \valid_read(core->cfg) && \separated(core, core->cfg);
  @ requires core->restart_history_len <= HA_MAX_RESTARTS_CAP;
  @ assigns core->restart_times_us[0 .. HA_MAX_RESTARTS_CAP - 1], core->restart_history_len;
  @ ensures history_only_in_window: \forall integer j; 0 <= j < core->restart_history_len ==>
  @   ha_elapsed(now_us, core->restart_times_us[j]) < core->cfg->restart_window_us;
  @ ensures history_keeps_every_recent: core->restart_history_len ==
  @   \at(ha_recent(&core->restart_times_us[0], core->restart_history_len, now_us,
  @                  core->cfg->restart_window_us), Pre);
  @ */
#endif
static void prune_restarts(HaCore *core, uint32_t now_us) {
  uint32_t kept = 0u, i;
#ifdef HA_WP
  /*@ loop invariant 0 <= kept <= i <= \at(core->restart_history_len, Pre);
    @ loop invariant core->cfg == \at(core->cfg, Pre) &&
    @   core->cfg->restart_window_us == \at(core->cfg->restart_window_us, Pre);
    @ loop invariant kept == ha_recent{Pre}(&core->restart_times_us[0], i, now_us,
    @                                       \at(core->cfg->restart_window_us, Pre));
    @ loop invariant \forall integer j; 0 <= j < kept ==>
    @   ha_elapsed(now_us, core->restart_times_us[j]) < \at(core->cfg->restart_window_us, Pre);
    @ loop invariant \forall integer j; i <= j < HA_MAX_RESTARTS_CAP ==>
    @   core->restart_times_us[j] == \at(core->restart_times_us[j], Pre);
    @ loop assigns kept, i, core->restart_times_us[0 .. HA_MAX_RESTARTS_CAP - 1];
    @ loop variant HA_MAX_RESTARTS_CAP - i;
    @ */
#endif
  for (i = 0u; i < core->restart_history_len && i < HA_MAX_RESTARTS_CAP; ++i) {
    if (ha_elapsed_us(now_us, core->restart_times_us[i]) < core->cfg->restart_window_us) {
      core->restart_times_us[kept++] = core->restart_times_us[i];
    }
  }
  core->restart_history_len = kept;
}

static int restart_cap_reached(const HaCore *core) {
  return core->restart_history_len >= core->cfg->max_restarts;
}

#ifdef HA_WP
/*@ requires \valid(core) && \valid(out) && \separated(core, out);
  @ requires core->restart_history_len <= HA_MAX_RESTARTS_CAP;
  @ assigns core->restart_times_us[0 .. HA_MAX_RESTARTS_CAP - 1], core->restart_history_len,
  @   core->restart_count, core->reset_active, core->reset_started_us, core->awaiting_boot,
  @   core->hp_up, out->restart_requested;
  @ ensures every_restart_counted: \old(core->restart_history_len) < HA_MAX_RESTARTS_CAP ==>
  @   core->restart_history_len == \old(core->restart_history_len) + 1 &&
  @   core->restart_times_us[\old(core->restart_history_len)] == now_us;
  @ ensures history_bounded: core->restart_history_len <= HA_MAX_RESTARTS_CAP;
  @ ensures reset_line_pulsed: core->reset_active == 1 && out->restart_requested == 1;
  @ */
#endif
static void request_restart(HaCore *core, uint32_t now_us, HaOutputs *out) {
  if (core->restart_history_len < HA_MAX_RESTARTS_CAP) {
    core->restart_times_us[core->restart_history_len++] = now_us;
  }
  if (core->restart_count < UINT16_MAX) {
    core->restart_count++;
  }
  core->reset_active = 1u;
  core->reset_started_us = now_us;
  core->awaiting_boot = 1u;
  core->hp_up = 0u;
  out->restart_requested = 1u;
}

/* The boot timeout runs from the release of the reset line: the HP cannot boot while held. */
static int boot_overdue(const HaCore *core, uint32_t now_us) {
  return core->awaiting_boot && !core->reset_active &&
         ha_elapsed_us(now_us, core->reset_released_us) >= core->cfg->hp_boot_timeout_us;
}

/* Operator requests never bypass a check: they only move the HA's own intent. Returns 1 for an
 * accepted RESTART_HP, which the policy then decides together with every other reason. */
static int handle_operator(HaCore *core, uint8_t command, const HaStateView *view, uint32_t now_us,
                           HaOutputs *out) {
  int accepted = 0, restart = 0;
  if (command == HA_OP_SELECT_HP && !core->latched) {
    core->ground_command = 0u;
    accepted = 1;
  } else if (command == HA_OP_SELECT_HA) {
    core->ground_command = 1u;
    accepted = 1;
  } else if (command == HA_OP_RESTART_HP && !core->latched &&
             core->controller != HA_CONTROLLER_HP) {
    restart = 1;
    accepted = 1;
  } else if (command == HA_OP_SELF_TEST && view->parked && core->controller != HA_CONTROLLER_HP &&
             core->controller != HA_CONTROLLER_MANUAL) {
    ha_self_test_start(&core->self_test, now_us);
    accepted = 1;
  }
  out->operator_accepted = (uint8_t)accepted;
  return restart;
}

/* Bookkeeping of a change of controller: why, the latch, a fresh stable window. */
static void on_switch(HaCore *core, uint8_t next, uint32_t reasons) {
  const int from_hp_side =
      core->controller == HA_CONTROLLER_HP || core->controller == HA_CONTROLLER_RECOVERING;
  const int to_ha = next == HA_CONTROLLER_HA || next == HA_CONTROLLER_HA_LATCHED;
  const int latching = next == HA_CONTROLLER_HA_LATCHED && !core->latched;
  if ((from_hp_side && to_ha) || latching) {
    core->reasons_at_switch = reasons; /* why the HP lost control, or why it lost it for good */
    core->stable_for_us = 0u;
  }
  if (latching) {
    core->latched = 1u;
  }
  core->controller = next;
}

static uint8_t choose_source(const HaCore *core) {
  if (core->controller == HA_CONTROLLER_MANUAL) return SRC_MANUAL;
  if (core->self_test.active) return SRC_SELF_TEST;
  if (core->controller == HA_CONTROLLER_HP) return SRC_HP;
  return SRC_HA;
}

static void fill_outputs(const HaCore *core, const HaStateView *view, const HaInputs *in,
                         uint32_t reasons, float sx_max, float su_max, HaOutputs *out) {
  out->surfaces = core->applied;
  out->controller = core->controller;
  out->reasons = reasons;
  out->reasons_at_switch = core->reasons_at_switch;
  out->restart_count = core->restart_count;
  out->hp_reset_asserted = core->reset_active;
  out->last_seq = core->last_seq;
  out->stable_for_s = (float)core->stable_for_us * 1.0e-6f;
  out->airspeed_ftps = view->airspeed_ftps;
  out->altitude_agl_ft = view->altitude_ok ? view->x[HA_X_ALT_AGL_FT] : 0.0f;
  out->alpha_deg = view->alpha_beta_ok ? in->hp_cmd.alpha_est_deg : 0.0f;
  out->beta_deg = view->alpha_beta_ok ? in->hp_cmd.beta_est_deg : 0.0f;
  out->state_region_max = sx_max;
  out->actuator_region_max = su_max;
  out->on_ground = view->on_ground;
  out->self_test_active = core->self_test.active;
}

/* The windows the hand-back waits out: the commands clear, the HA's own state whole. */
static void update_windows(HaCore *core, uint32_t reasons, uint32_t dt_us) {
  core->stable_for_us =
      (reasons & HA_REASONS_COMMAND) ? 0u : ha_add_sat(core->stable_for_us, dt_us);
  core->own_state_for_us =
      (reasons & HA_REASON_NO_HA_STATE) ? 0u : ha_add_sat(core->own_state_for_us, dt_us);
  if (!(reasons & HA_REASONS_COMMAND)) {
    core->awaiting_boot = 0u; /* the HP is back */
    core->hp_up = 1u;
  }
}

/* The policy's inputs but the operator's restart (handle_operator's). */
static void fill_policy(HaCore *core, const HaInputs *in, const HaStateView *view,
                        const HaCmdFacts *facts, uint32_t reasons, float sx_max, uint32_t now_us,
                        HaPolicyIn *policy) {
  const HaAircraftConfig *cfg = core->cfg;
  policy->controller = core->controller;
  policy->manual = (uint8_t)(in->rc.valid && in->rc.pulse_us[HA_RC_PIC] >= cfg->pic_threshold_us);
  if (policy->manual || !view->parked) {
    core->self_test.active = 0u; /* the pilot or a lift-off ends the self-test */
  }
  policy->latched = core->latched;
  policy->self_test = core->self_test.active;
  policy->ground_command = core->ground_command;
  policy->reasons = reasons;
  policy->stable = (uint8_t)(core->stable_for_us >= cfg->stable_window_us);
  /* The HA hands back only on a state it has had whole for the stable window too: an INS that
   * comes every 150 ms, stale every other period, otherwise swapped the controller 86 times a
   * minute, each hand-back on one fresh state. */
  policy->inner =
      (uint8_t)(!(reasons & HA_REASONS_STATE) && !ha_greater(sx_max, cfg->inner_region_fraction) &&
                (!view->airborne || ha_greater(view->airspeed_ftps, cfg->handback_airspeed_ftps)) &&
                core->own_state_for_us >= cfg->stable_window_us);
  policy->restart_cap_reached = (uint8_t)restart_cap_reached(core);
  policy->boot_overdue = (uint8_t)boot_overdue(core, now_us);
  /* An HP that had been up and fails while the pilot or the operator's HA flies is restarted as
   * if it had lost control: silent, or alive but failing a check (its sensor link lost). An HP
   * still booting at power-up (estimator not yet converged) has never been up. */
  policy->hp_failed = (uint8_t)(!core->awaiting_boot && !core->reset_active &&
                                ((facts->have_cmd && (reasons & HA_REASON_NO_COMMAND)) ||
                                 (core->hp_up && (reasons & HA_REASONS_COMMAND))));
}

/* What reaches the servos this period, from its source, eased through a transition and
 * saturated into S_u whatever the source. */
static void drive_servos(HaCore *core, const HaInputs *in, const HaStateView *view,
                         const HaSurfaces *ha_cmd, uint32_t now_us, float dt_s) {
  const HaAircraftConfig *cfg = core->cfg;
  uint8_t source = choose_source(core);
  HaSurfaces target = *ha_cmd;
  if (source == SRC_MANUAL) {
    ha_surfaces_from_rc(cfg, &in->rc, &target);
  } else if (source == SRC_HP) {
    ha_surfaces_from_cmd(&in->hp_cmd, &target); /* every check passed: finite, inside S_u */
  } else if (source == SRC_SELF_TEST &&
             !ha_self_test_target(&core->self_test, cfg, now_us, &target)) {
    target = *ha_cmd; /* the sequence just ended */
    source = SRC_HA;
  }
  if (source != core->last_source || source == SRC_SELF_TEST) {
    core->transition_active = 1u;
  }
  if (source == SRC_MANUAL) {
    /* Bumpless transfer is for the computers, not the pilot: a safety pilot who flips the switch
     * to save the aircraft gets the sticks on the servos in this very period, as PX4 and
     * ArduPilot give manual control (a rate-limited handover took 0.67 s to full deflection). */
    core->transition_active = 0u;
  }
  if (core->transition_active) {
    HaSurfaces limited;
    /* Inside S_u already (the checks passed), saturated all the same so that the limiter's
     * arithmetic is bounded for static analysis too. The other sources are in S_u by
     * construction (the sticks are saturated, the safety controller clamps each output, the
     * self-test's are the limits), and saturating every target twice cost 4 compares a period. */
    if (source == SRC_HP) {
      ha_surfaces_saturate(cfg, &target);
    }
    core->transition_active = (uint8_t)!ha_surfaces_rate_limit(
        cfg, &core->applied, &target, dt_s, view->stalling && source == SRC_HA, &limited);
    target = limited;
  }
  ha_surfaces_saturate(cfg, &target); /* the last word: nothing outside S_u reaches a servo */
  core->applied = target;
  core->last_source = source;
}

void ha_core_step(HaCore *core, const HaInputs *in, uint32_t now_us, HaOutputs *out) {
  const HaAircraftConfig *cfg = core->cfg;
  const uint32_t dt_us = period_dt_us(core, now_us);
  const float dt_s = (float)dt_us * 1.0e-6f;
  HaCmdFacts facts;
  HaStateView view;
  HaPolicyIn policy;
  HaSurfaces ha_cmd;
  float sx_max = 0.0f, su_max = 0.0f;
  uint32_t reasons;

  out->restart_requested = 0u;
  track_command(core, in, now_us, dt_us, &facts);
  track_own_sensors(core, in, now_us, dt_us);
  ha_state_view(cfg, in, facts.cmd, facts.have_cmd, &core->own, &view);
  ha_airdata_view(&core->airdata, cfg, &view);
  decide_airborne(core, dt_us, &view);
  policy.operator_restart =
      (uint8_t)handle_operator(core, in->operator_command, &view, now_us, out);
  reasons = ha_checks_evaluate(cfg, &facts, &view, &sx_max, &su_max) |
            (core->ground_command ? HA_REASON_GROUND_COMMAND : 0u);
  /* The stall is flown out only on a speed the HA may fly by: the INS's speed over the ground,
   * the wind unknown, reads a headwind as a stall, and a push on it dives a healthy aircraft. */
  view.stalling = (uint8_t)((reasons & HA_REASON_STALL) != 0u && view.speed_known);
  update_windows(core, reasons, dt_us);
  prune_restarts(core, now_us);
  fill_policy(core, in, &view, &facts, reasons, sx_max, now_us, &policy);
  {
    const uint8_t next = ha_policy_decide(&policy);
    const uint8_t restart = ha_policy_restart(&policy, next);
    if (next != core->controller) {
      on_switch(core, next, reasons);
    }
    if (restart) {
      request_restart(core, now_us, out);
    }
  }

  /* The safety controller runs every period; it tracks the applied surfaces unless it was the
   * source last period, so that it starts from them. From then on it flies, the rate limiter
   * easing the servos to it: tracking through the handover left pitch and roll unflown while
   * the throttle (0.5 a second) or the yaw damper's rudder still eased (HiL campaign seed 27 #5:
   * 1.08 s with the elevator frozen at 1.9 deg of pull while a gust put 1.9 g on the wing and
   * stalled it; the lift guard's push went into the tracking integrator). */
  ha_safety_ctrl_step(&core->sc, cfg, &view, &core->applied, core->last_source == SRC_HA, dt_s,
                      &ha_cmd);
  drive_servos(core, in, &view, &ha_cmd, now_us, dt_s);

  if (core->reset_active &&
      ha_elapsed_us(now_us, core->reset_started_us) >= cfg->hp_reset_pulse_us) {
    core->reset_active = 0u;
    core->reset_released_us = now_us;
  }
  core->have_step = 1u;
  core->last_step_us = now_us;
  fill_outputs(core, &view, in, reasons, sx_max, su_max, out);
  out->ha_command = ha_cmd;
}
