/* Surface vectors: saturation into S_u, rate limiting across switches, RC and HP mapping. */
#ifndef HA_SURFACES_H
#define HA_SURFACES_H

#include "ha_core.h"

#ifdef __cplusplus
extern "C" {
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
