// MAVLink mission frames and the two item messages: which frames a waypoint may use, how its
// altitude becomes a height above home, and the conversion between the wire messages and the one
// stored MissionItem. No I/O, no time.
#pragma once

#include <cstdint>

#include "geo.h"
#include "mavlink_all.h"
#include "mission.h"

namespace microhard_gs {

// MAV_FRAME_GLOBAL (0), GLOBAL_RELATIVE_ALT (3) and their deprecated _INT twins (5, 6): the
// frames a waypoint may be given in, in either item message.
bool is_global_frame(uint8_t frame);

// Height above home [ft] of an altitude `z_m` given in `frame`. Relative frames (3, 6) are
// already above home. Absolute frames (0, 5) are MSL; the vehicle's one altitude datum is the
// INS's, which is also what it reports as MSL (GLOBAL_POSITION_INT.alt, HOME_POSITION.altitude),
// so the height is z - home altitude. False for a non-global frame or a non-finite altitude.
bool height_above_home_ft(uint8_t frame, float z_m, const GeoPoint& home, double* height_ft);

// The wire messages to and from the stored item. The stored item keeps the frame as uploaded;
// latitude/longitude are deg * 1e7 whichever message carried them (MISSION_ITEM carries degrees).
MissionItem from_item_int(const mavlink_mission_item_int_t& m);
MissionItem from_item_float(const mavlink_mission_item_t& m);
// Downloads answer in the frame the item was uploaded in. A MISSION_ITEM carries degrees, so an
// item uploaded in an _INT frame (5, 6) goes out in its float twin (0, 3) there.
mavlink_mission_item_int_t to_item_int(const MissionItem& it);
mavlink_mission_item_t to_item_float(const MissionItem& it);

}  // namespace microhard_gs
