// The ground-station configuration the core's tests and its fuzz harness share: DG808-like
// mission limits and a fixed-home GsConfig. Each test changes only what its story needs.
#ifndef MICROHARD_GS_TEST_GS_TEST_CONFIG_H
#define MICROHARD_GS_TEST_GS_TEST_CONFIG_H

#include "gs_core.h"

namespace microhard_gs {
namespace test {

inline MissionLimits mission_limits() {
  MissionLimits l;
  l.floor_ft = 100.0;
  l.ceiling_ft = 400.0;
  l.max_radius_ft = 3000.0;
  l.min_speed_ftps = 42.0;
  l.default_speed_ftps = 60.0;
  return l;
}

// No home: a test that needs one gives the core the HA's (set_home, as /home does).
inline GsConfig gs_config(double telemetry_rate_hz = 10.0) {
  GsConfig c;
  c.system_id = 1;
  c.telemetry_rate_hz = telemetry_rate_hz;
  c.mission.limits = mission_limits();
  c.airborne_agl_ft = 30.0;
  return c;
}

}  // namespace test
}  // namespace microhard_gs

#endif
