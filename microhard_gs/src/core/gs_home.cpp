// Home from its one owner, the HA, which latches it from its own INS (first 3D fix while parked)
// and publishes it on the latched /home. The ground station never latches its own: /way is built
// from the same home the controller flies it from and the HA circles.
#include <cmath>
#include <vector>

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
    send_home_position();
    send_statustext(MAV_SEVERITY_INFO, "Home set by the HA");
  }
  return true;
}

// MAV_CMD_DO_SET_HOME: param1 1 = here (where the HA's INS says the aircraft is), 0 = the
// position in params 5-7 (altitude: WGS84 ellipsoid height, as HOME_POSITION reports it). Only on
// the ground: moving the origin of /way, of the HA's circle and of its ceiling in flight would
// shift all three under the aircraft. The HA refuses it in the air too (ha_ins_set_home), and
// decides: ACCEPTED means forwarded, the new home comes back on /home as HOME_POSITION.
uint8_t GsCore::set_home_command(float use_current, double lat_deg, double lon_deg, float alt_m) {
  if (!vehicle_.have_decision) {
    send_statustext(MAV_SEVERITY_WARNING,
                    "Set home refused: no HA status, cannot tell it is on the ground");
    return MAV_RESULT_TEMPORARILY_REJECTED;
  }
  if (vehicle_.decision.altitude_agl_ft > config_.airborne_agl_ft) {
    send_statustext(MAV_SEVERITY_WARNING, "Set home refused: in flight");
    return MAV_RESULT_TEMPORARILY_REJECTED;
  }
  HomeRequest r;
  r.use_current = use_current == 1.0f;
  if (!r.use_current) {
    if (use_current != 0.0f || !is_valid_home(GeoPoint{lat_deg, lon_deg, alt_m})) {
      send_statustext(MAV_SEVERITY_WARNING, "Set home refused: not a valid position");
      return MAV_RESULT_DENIED;
    }
    r.position.lat_deg = lat_deg;
    r.position.lon_deg = lon_deg;
    r.position.alt_m = alt_m;
  }
  home_requests_.push_back(r);
  return MAV_RESULT_ACCEPTED;
}

std::vector<HomeRequest> GsCore::take_home_requests() {
  std::vector<HomeRequest> out;
  out.swap(home_requests_);
  return out;
}

}  // namespace microhard_gs
