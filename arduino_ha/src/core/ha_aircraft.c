#include "ha_aircraft.h"

/* Host builds pass the header CMake regenerated from limits.yaml; arduino-cli, which cannot
 * run the generator, compiles the checked-in copy (a test keeps the two identical). */
#ifdef HA_AIRCRAFT_CONFIG_HEADER
#include HA_AIRCRAFT_CONFIG_HEADER
#else
#include "../generated/aircraft_config.h"
#endif

const HaAircraftConfig ha_aircraft_config = HA_AIRCRAFT_CONFIG_INITIALIZER;
