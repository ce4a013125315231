/* Surface vectors: saturation into S_u, rate limiting across switches, RC and HP mapping. */
#ifndef HA_SURFACES_H
#define HA_SURFACES_H

#include "ha_core.h"

#ifdef __cplusplus
extern "C" {
#endif

#ifdef HA_WP        /* for make prove-ha (README.md, "Proofs") */
#include "ha_num.h" /* ha_within, ha_neg */
/*@ predicate ha_limit_ok(float limit) = \is_finite(limit) && \le_float((float)0.0, limit);
  @ // The box S_u is built from (ha_config.h), as the generator writes it: finite, ordered.
  @ predicate ha_su_box(HaAircraftConfig *cfg) =
  @   ha_limit_ok(cfg->elevator_limit_deg) && ha_limit_ok(cfg->aileron_limit_deg) &&
  @   ha_limit_ok(cfg->rudder_limit_deg) && \is_finite(cfg->throttle_min) &&
  @   \is_finite(cfg->throttle_max) && \le_float(cfg->throttle_min, cfg->throttle_max);
  @ // Every surface finite and inside S_u.
  @ predicate ha_in_su(HaAircraftConfig *cfg, HaSurfaces s) =
  @   ha_within(s.elevator_deg, ha_neg(cfg->elevator_limit_deg), cfg->elevator_limit_deg) &&
  @   ha_within(s.aileron_deg, ha_neg(cfg->aileron_limit_deg), cfg->aileron_limit_deg) &&
  @   ha_within(s.rudder_deg, ha_neg(cfg->rudder_limit_deg), cfg->rudder_limit_deg) &&
  @   ha_within(s.throttle, cfg->throttle_min, cfg->throttle_max);
  @ */
#endif

/* Into the actuator box; a non-finite value becomes the in-range value nearest neutral. */
void ha_surfaces_saturate(const HaAircraftConfig *cfg, HaSurfaces *s);

/* Moves prev towards target by at most the configured rate over dt_s; returns 1 when out equals
 * target (the transition is over). unloading: the HA's own command on a stalling wing, whose
 * nose-down elevator moves at the release rate. */
int ha_surfaces_rate_limit(const HaAircraftConfig *cfg, const HaSurfaces *prev,
                           const HaSurfaces *target, float dt_s, int unloading, HaSurfaces *out);

/* The pilot's sticks: pulse [min, max] onto [-limit, +limit]; out-of-range pulses clamp. */
void ha_surfaces_from_rc(const HaAircraftConfig *cfg, const HaRcInputs *rc, HaSurfaces *out);

void ha_surfaces_from_cmd(const HaHpCommand *cmd, HaSurfaces *out);

#ifdef __cplusplus
}
#endif

#endif /* HA_SURFACES_H */
