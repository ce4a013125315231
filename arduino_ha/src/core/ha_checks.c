#include "ha_checks.h"

#include "ha_num.h"
#include "ha_region.h"

#define HA_RAD_PER_DEG 0.017453293f

static uint32_t flag(int failed, uint32_t reason) { return failed ? reason : 0u; }

static int surfaces_finite(const HaHpCommand *c) {
  return ha_finite(c->throttle) && ha_finite(c->elevator_deg) && ha_finite(c->aileron_deg) &&
         ha_finite(c->rudder_deg);
}

/* HP crashed: nothing at all within the timeout. */
static uint32_t check_no_command(const HaAircraftConfig *cfg, const HaCmdFacts *f) {
  return flag(!f->have_cmd || f->age_us > cfg->no_command_timeout_us, HA_REASON_NO_COMMAND);
}

/* Late: more consecutive periods without a new command than tolerated. */
static uint32_t check_deadline(const HaAircraftConfig *cfg, const HaCmdFacts *f) {
  return flag(f->late_periods > cfg->late_periods_tolerated, HA_REASON_DEADLINE_MISS);
}

static uint32_t check_finite(const HaHpCommand *c) {
  return flag(!surfaces_finite(c) || !ha_finite(c->alpha_est_deg) || !ha_finite(c->beta_est_deg),
              HA_REASON_NOT_FINITE);
}

static uint32_t check_actuator_region(const HaAircraftConfig *cfg, const HaHpCommand *c,
                                      float *region_max) {
  float u[HA_U_DIM];
  u[HA_U_ELEVATOR_DEG] = c->elevator_deg;
  u[HA_U_AILERON_DEG] = c->aileron_deg;
  u[HA_U_RUDDER_DEG] = c->rudder_deg;
  u[HA_U_THROTTLE] = c->throttle;
  *region_max = ha_actuator_region_max(cfg, u);
  /* The box S_u is built from is checked exactly too: float rounding of S_u u can round a value
   * a hair outside (say a negative denormal throttle) onto the boundary. An accepted command
   * therefore passes the final saturation unchanged. */
  const int in_box =
      ha_in_range(c->elevator_deg, -cfg->elevator_limit_deg, cfg->elevator_limit_deg) &&
      ha_in_range(c->aileron_deg, -cfg->aileron_limit_deg, cfg->aileron_limit_deg) &&
      ha_in_range(c->rudder_deg, -cfg->rudder_limit_deg, cfg->rudder_limit_deg) &&
      ha_in_range(c->throttle, cfg->throttle_min, cfg->throttle_max);
  return flag(ha_greater(*region_max, 1.0f) || !in_box, HA_REASON_ACTUATOR_REGION);
}

/* Airborne, a pull the wing cannot take: more nose-up elevator than elevator_pull_limit_deg
 * trims it far past its stall whatever the speed, and at cruise speed it is an accelerated stall
 * within a few periods, before the stall check can see it (HiL low_slow: full up at 84 ft/s, 4 g
 * and the wing stalled 0.16 s after the command). Judged on the command, before it is applied. */
static uint32_t check_pull(const HaAircraftConfig *cfg, const HaHpCommand *c,
                           const HaStateView *s) {
  return flag(s->airborne && ha_greater(-c->elevator_deg, cfg->elevator_pull_limit_deg),
              HA_REASON_PULL);
}

/* Estimator divergence: the HP's own alpha/beta beyond their limits. */
static uint32_t check_alpha_beta(const HaAircraftConfig *cfg, const HaHpCommand *c) {
  return flag(!ha_in_range(c->alpha_est_deg, -cfg->alpha_limit_deg, cfg->alpha_limit_deg) ||
                  !ha_in_range(c->beta_est_deg, -cfg->beta_limit_deg, cfg->beta_limit_deg),
              HA_REASON_ALPHA_BETA);
}

static uint32_t check_sensor_link(const HaHpCommand *c) {
  return flag(c->sensor_links_healthy != 1u, HA_REASON_SENSOR_LINK);
}

static uint32_t check_estimator(const HaHpCommand *c) {
  return flag(c->estimator_converged != 1u, HA_REASON_ESTIMATOR);
}

static uint32_t check_frozen(const HaCmdFacts *f) { return flag(f->frozen, HA_REASON_FROZEN); }

static uint32_t check_integrity(const HaCmdFacts *f) {
  return flag(!f->intact, HA_REASON_INTEGRITY);
}

/* The HA cannot judge the state checks: its INS state is stale or invalid, or in flight its
 * pitot has failed for longer than a glitch. Said as such, not as a ceiling or region breach. */
static uint32_t check_ha_state(const HaStateView *s) {
  return flag(!s->attitude_ok || !s->altitude_ok || (s->airborne && !s->airspeed_ok),
              HA_REASON_NO_HA_STATE);
}

/* Pitch less flight path at or past stall_alpha cos(bank): climb <= k TAS with k = (pitch -
 * stall_alpha cos(bank)) in rad (small angles), decided in squares (the INS's TAS squared: no
 * root). */
static int past_stall_alpha(const HaAircraftConfig *cfg, const HaStateView *s) {
  const float k = (s->x[HA_X_PITCH_DEG] - cfg->stall_alpha_deg * s->cos_bank) * HA_RAD_PER_DEG;
  const float climb_sq = s->climb_ftps * s->climb_ftps;
  const float bound_sq = k * k * s->path_tas_sq;
  if (!ha_greater(k, 0.0f)) { /* the bound is a descent: descending at least that steeply */
    return ha_greater(0.0f, s->climb_ftps) && !ha_greater(bound_sq, climb_sq);
  }
  return !ha_greater(s->climb_ftps, 0.0f) || !ha_greater(climb_sq, bound_sq);
}

/* Airborne and stalling, by either sign. Slow: at or below the stall switch speed times
 * sqrt(load factor), IAS^2 <= V_switch^2 n (squares: no root), with the load factor the gyros
 * see (ha_airdata.c: 1 / cos(bank) in a level turn, more in a pull); the speed is the pitot's,
 * or the INS's less the wind when the pitot is not believed. The pitot lags a stall by several
 * periods, so waiting for stall speed itself hands the HA a departed aircraft. Or, below the
 * 1 g hand-back speed (near_stall, ha_airdata.c), past the airframe's stall angle of attack
 * (stall_alpha_deg, which the generator holds to airframe.yaml's): pitch less flight path is
 * alpha cos(bank), a stalled glide that the speed does not show. Only there: the INS's flight
 * path cannot see a vertical gust, and in moderate turbulence a downdraft at cruise read as
 * alpha 9 deg at a true 1.5 (HiL) and took a healthy HP out for good. */
static uint32_t check_stall(const HaAircraftConfig *cfg, const HaStateView *s) {
  const int slow =
      s->speed_ok && !ha_greater(s->ias_sq, cfg->stall_switch_airspeed_sq * s->load_factor);
  return flag(s->airborne && (slow || (s->alpha_ok && past_stall_alpha(cfg, s))), HA_REASON_STALL);
}

/* Within the switch margin of the ceiling: the INS's height error and the climb during the
 * takeover must not carry the aircraft through it (a component not ok holds the region centre,
 * so only known values count). */
static uint32_t check_ceiling(const HaAircraftConfig *cfg, const HaStateView *s) {
  return flag(ha_greater(s->x[HA_X_ALT_AGL_FT], cfg->ceiling_switch_agl_ft), HA_REASON_CEILING);
}

static uint32_t check_state_region(const HaAircraftConfig *cfg, const HaStateView *s,
                                   float *region_max) {
  *region_max = ha_state_region_max(cfg, s->x);
  return flag(ha_greater(*region_max, cfg->switch_region_fraction), HA_REASON_STATE_REGION);
}

uint32_t ha_checks_evaluate(const HaAircraftConfig *cfg, const HaCmdFacts *facts,
                            const HaStateView *state, float *state_region_max,
                            float *actuator_region_max) {
  uint32_t reasons = check_no_command(cfg, facts) | check_deadline(cfg, facts) |
                     check_ha_state(state) | check_stall(cfg, state) | check_ceiling(cfg, state) |
                     check_state_region(cfg, state, state_region_max);
  *actuator_region_max = 0.0f;
  if (facts->have_cmd) {
    const HaHpCommand *c = facts->cmd;
    reasons |= check_finite(c) | check_alpha_beta(cfg, c) | check_sensor_link(c) |
               check_estimator(c) | check_frozen(facts) | check_integrity(facts) |
               check_pull(cfg, c, state);
    /* A non-finite surface cannot be shown inside S_u: it fails the region too. */
    reasons |= surfaces_finite(c) ? check_actuator_region(cfg, c, actuator_region_max)
                                  : HA_REASON_ACTUATOR_REGION;
  }
  return reasons;
}
