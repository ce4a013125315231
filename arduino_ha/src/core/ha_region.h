/* Safety regions in matrix form: max_i (S (v - v0))_i, inside while <= 1. */
#ifndef HA_REGION_H
#define HA_REGION_H

#include "../generated/ha_config.h"

/* x as ha_state_view leaves it: every component clamped to its plausibility span, which keeps
 * the arithmetic finite. u may be anything (its components are clamped here). */
float ha_state_region_max(const HaAircraftConfig *cfg, const float x[HA_X_DIM]);
float ha_actuator_region_max(const HaAircraftConfig *cfg, const float u[HA_U_DIM]);

#endif /* HA_REGION_H */
