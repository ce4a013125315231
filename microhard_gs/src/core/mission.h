// Mission items as plain structs, their validation against the aircraft's limits, and the
// conversion of an accepted mission into the `way` flight plan. No I/O, no time.
#pragma once

#include <cstdint>
#include <string>

#include "geo.h"

namespace microhard_gs {

// The `way` message holds at most 32 waypoints; a mission never has more items than that.
constexpr int kMaxMissionItems = 32;

// A MISSION_ITEM_INT's fields, copied out of the packed wire struct. Legacy float items
// (MISSION_ITEM) are stored in this form too, lat/lon scaled by 1e7; the frame is kept as
// uploaded (mission_frames.h), so a download answers in it.
struct MissionItem {
  uint16_t seq = 0;
  uint8_t frame = 0;
  uint16_t command = 0;
  uint8_t current = 0;
  uint8_t autocontinue = 1;
  float param1 = 0.0f;
  float param2 = 0.0f;
  float param3 = 0.0f;
  float param4 = 0.0f;
  int32_t x = 0;   // latitude [deg * 1e7]
  int32_t y = 0;   // longitude [deg * 1e7]
  float z = 0.0f;  // altitude [m], meaning set by frame
};

struct MissionLimits {
  double floor_ft = 0.0;            // lowest height above home accepted
  double ceiling_ft = 0.0;          // highest height above home accepted (limits.yaml)
  double max_radius_ft = 0.0;       // farthest horizontal distance from home accepted
  double min_speed_ftps = 0.0;      // slowest commanded airspeed accepted (stall, limits.yaml)
  double default_speed_ftps = 0.0;  // leg airspeed until a DO_CHANGE_SPEED says otherwise
};

// A MAV_MISSION_RESULT and, when it is not ACCEPTED, a sentence for the operator's STATUSTEXT.
struct MissionVerdict {
  uint8_t result = 0;
  std::string reason;
  bool ok() const { return result == 0; }
};

struct WayPlan {
  int32_t fp = 0;
  double north_ft[kMaxMissionItems] = {};
  double east_ft[kMaxMissionItems] = {};
  double height_ft[kMaxMissionItems] = {};
  double velocity_ftps[kMaxMissionItems] = {};
  int item_seq[kMaxMissionItems] =
      {};  // the mission item each waypoint came from (MISSION_CURRENT)
};

// Item 0 as home (ArduPilot's convention, which MAVProxy's and QGroundControl's ArduPilot-mode
// waypoint files follow): a NAV_WAYPOINT at seq 0 whose height above home is below the mission
// floor is the home row. It is not flown and does not move the vehicle's home; it is checked as a
// position (valid, inside the radius) and kept, so a download gives the file back. A seq-0
// waypoint at or above the floor is flown like any other: a GCS that does not send home
// (QGroundControl with a generic autopilot) puts its first waypoint there.
bool is_home_row(const MissionItem& item, const GeoPoint& home, const MissionLimits& limits);

// Checks one item on its own: supported command and frame, position valid, height within
// [floor, ceiling] above home (the home row: below the floor), inside the radius, speed not below
// stall.
MissionVerdict check_mission_item(const MissionItem& item, const GeoPoint& home,
                                  const MissionLimits& limits);

// Checks a whole mission and, when every item passes, fills `plan`. `plan` is untouched on
// rejection, so the caller's previous mission stays.
MissionVerdict build_way_plan(const MissionItem* items, int count, const GeoPoint& home,
                              const MissionLimits& limits, WayPlan* plan);

}  // namespace microhard_gs
