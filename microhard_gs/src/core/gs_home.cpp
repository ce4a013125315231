// Home from its one owner, the HA, which latches it from its own INS (first 3D fix while parked)
// and publishes it on the latched /home. The ground station never latches its own: /way is built
// from the same home the controller flies it from and the HA circles.
#include <cmath>

#include "gs_core.h"

namespace microhard_gs {

bool GsCore::set_home(const GeoPoint& home) {
  if (!is_valid_position(home.lat_deg, home.lon_deg) || !std::isfinite(home.alt_m)) {
    return false;
  }
  const bool moved = !home_known_ || home.lat_deg != home_.lat_deg ||
                     home.lon_deg != home_.lon_deg || home.alt_m != home_.alt_m;
  home_ = home;
  home_known_ = true;
  if (moved) {
    send_home_position();
    send_statustext(MAV_SEVERITY_INFO, "Home set by the HA");
  }
  return true;
}

}  // namespace microhard_gs
