/* The aircraft this firmware is built for: the generated configuration as one const object,
 * so C++ code (the sketch, the tests) never has to compile the C99 designated initializer. */
#ifndef HA_AIRCRAFT_H
#define HA_AIRCRAFT_H

#include "../generated/ha_config.h"

#ifdef __cplusplus
extern "C" {
#endif

extern const HaAircraftConfig ha_aircraft_config;

#ifdef __cplusplus
}
#endif

#endif /* HA_AIRCRAFT_H */
