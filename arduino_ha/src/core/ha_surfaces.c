#include "ha_surfaces.h"

#include "ha_num.h"

#ifdef HA_WP /* make prove-ha (README.md, "Proofs") */
/*@ requires \valid(s) && \valid_read(cfg) && \separated(s, cfg);
  @ requires su_box: ha_su_box(cfg);
  @ assigns *s;
  @ ensures saturated_in_su: ha_in_su(cfg, *s);
  @ ensures in_su_unchanged: ha_in_su(cfg, \old(*s)) ==>
  @   \eq_float(s->elevator_deg, \old(s->elevator_deg)) &&
  @   \eq_float(s->aileron_deg, \old(s->aileron_deg)) &&
  @   \eq_float(s->rudder_deg, \old(s->rudder_deg)) && \eq_float(s->throttle, \old(s->throttle));
  @ */
#endif
void ha_surfaces_saturate(const HaAircraftConfig *cfg, HaSurfaces *s) {
  s->elevator_deg = ha_clampf(s->elevator_deg, -cfg->elevator_limit_deg, cfg->elevator_limit_deg);
  s->aileron_deg = ha_clampf(s->aileron_deg, -cfg->aileron_limit_deg, cfg->aileron_limit_deg);
  s->rudder_deg = ha_clampf(s->rudder_deg, -cfg->rudder_limit_deg, cfg->rudder_limit_deg);
  s->throttle = ha_clampf(s->throttle, cfg->throttle_min, cfg->throttle_max);
}

static float step_towards(float prev, float target, float max_step, int *reached) {
  const float delta = target - prev;
  if (delta > max_step) {
    *reached = 0;
    return prev + max_step;
  }
  if (delta < -max_step) {
    *reached = 0;
    return prev - max_step;
  }
  return target;
}

/* A pull (trailing edge up, negative) that the new controller eases towards neutral goes at the
 * release rate: bumpless transfer must not keep the last controller's pull on a wing it is
 * stalling (HiL: 0.3 s of an HP's pull slewed out at 60 deg/s took the wing to 24 deg of alpha
 * after a STALL takeover). Past neutral, and every pull, at the bumpless rate; but the HA
 * unloading a stall moves nose down at the release rate all the way (HiL campaign seed 25 #94:
 * eased past neutral at 60 deg/s, the HP's inherited 21 deg/s pitch-up carried the wing 0.02 s
 * past its stall). */
static float elevator_towards(const HaAircraftConfig *cfg, float prev, float target, float dt_s,
                              int unloading, int *reached) {
  const float bumpless =
      step_towards(prev, target, cfg->surface_rate_limit_deg_per_s * dt_s, reached);
  if (unloading && ha_greater(target, bumpless)) {
    /* *reached is 0 already: the bumpless step fell short of the target. */
    return step_towards(prev, target, cfg->surface_release_rate_deg_per_s * dt_s, reached);
  }
  if (ha_greater(0.0f, prev) && ha_greater(target, bumpless)) {
    int released = 1;
    const float released_deg = step_towards(prev, ha_greater(0.0f, target) ? target : 0.0f,
                                            cfg->surface_release_rate_deg_per_s * dt_s, &released);
    return ha_greater(released_deg, bumpless) ? released_deg : bumpless;
  }
  /* A push (trailing edge down) being eased back, as far as neutral, at the release rate too: it
   * went on at that rate to unload a stall, and taken off at the bumpless rate it outlived the
   * command that asked for it by a quarter second (HiL campaign seed 27 #111: an 18 deg push
   * whose command was a 2.5 deg pull 0.25 s later still pushed 11 deg on the servo; -0.8 g and
   * the nose 9 deg past the -10 deg the HA asked for). */
  if (ha_greater(prev, 0.0f) && ha_greater(bumpless, target)) {
    int released = 1;
    const float released_deg = step_towards(prev, ha_greater(target, 0.0f) ? target : 0.0f,
                                            cfg->surface_release_rate_deg_per_s * dt_s, &released);
    return ha_greater(bumpless, released_deg) ? released_deg : bumpless;
  }
  return bumpless;
}

int ha_surfaces_rate_limit(const HaAircraftConfig *cfg, const HaSurfaces *prev,
                           const HaSurfaces *target, float dt_s, int unloading, HaSurfaces *out) {
  const float surface_step = cfg->surface_rate_limit_deg_per_s * dt_s;
  const float throttle_step = cfg->throttle_rate_limit_per_s * dt_s;
  int reached = 1;
  out->elevator_deg =
      elevator_towards(cfg, prev->elevator_deg, target->elevator_deg, dt_s, unloading, &reached);
  out->aileron_deg = step_towards(prev->aileron_deg, target->aileron_deg, surface_step, &reached);
  out->rudder_deg = step_towards(prev->rudder_deg, target->rudder_deg, surface_step, &reached);
  out->throttle = step_towards(prev->throttle, target->throttle, throttle_step, &reached);
  return reached;
}

/* Microseconds above the range's minimum, the pulse clamped to the range first: integer work,
 * and the value is exact in a float. */
static float pulse_above_min_us(const HaAircraftConfig *cfg, uint16_t pulse_us) {
  uint32_t p = pulse_us;
  p = p < cfg->rc_pulse_min_us ? cfg->rc_pulse_min_us : p;
  p = p > cfg->rc_pulse_max_us ? cfg->rc_pulse_max_us : p;
  return (float)(p - cfg->rc_pulse_min_us);
}

void ha_surfaces_from_rc(const HaAircraftConfig *cfg, const HaRcInputs *rc, HaSurfaces *out) {
  out->elevator_deg =
      pulse_above_min_us(cfg, rc->pulse_us[HA_RC_ELEVATOR]) * cfg->rc_elevator_deg_per_us -
      cfg->elevator_limit_deg;
  out->aileron_deg =
      pulse_above_min_us(cfg, rc->pulse_us[HA_RC_AILERON]) * cfg->rc_aileron_deg_per_us -
      cfg->aileron_limit_deg;
  out->rudder_deg =
      pulse_above_min_us(cfg, rc->pulse_us[HA_RC_RUDDER]) * cfg->rc_rudder_deg_per_us -
      cfg->rudder_limit_deg;
  out->throttle = pulse_above_min_us(cfg, rc->pulse_us[HA_RC_THROTTLE]) * cfg->rc_throttle_per_us +
                  cfg->throttle_min;
  ha_surfaces_saturate(cfg, out); /* a rounding at either end stays inside S_u */
}

void ha_surfaces_from_cmd(const HaHpCommand *cmd, HaSurfaces *out) {
  out->throttle = cmd->throttle;
  out->elevator_deg = cmd->elevator_deg;
  out->aileron_deg = cmd->aileron_deg;
  out->rudder_deg = cmd->rudder_deg;
}
