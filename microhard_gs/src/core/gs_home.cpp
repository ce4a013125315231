// Home from its one owner, the HA, which latches it from its own INS (first 3D fix while parked)
// and publishes it on the latched /home. The ground station never latches its own: /way is built
// from the same home the controller flies it from and the HA circles.
// A SET_HOME from the ground is a request the HA decides (CommandService::set_home).
#include "gs_core.h"

namespace microhard_gs {

bool GsCore::set_home(const GeoPoint& home) {
  if (!is_valid_home(home)) {
    return false;
  }
  const bool moved = !vehicle_.home_known || home.lat_deg != vehicle_.home.lat_deg ||
                     home.lon_deg != vehicle_.home.lon_deg || home.alt_m != vehicle_.home.alt_m;
  vehicle_.home = home;
  vehicle_.home_known = true;
  if (moved) {
    telemetry_.send_home_position();
    out_.statustext(MAV_SEVERITY_INFO, "Home set by the HA");
  }
  return true;
}

}  // namespace microhard_gs
