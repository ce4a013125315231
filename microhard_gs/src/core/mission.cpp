#include "mission.h"

#include <cmath>
#include <cstdarg>
#include <cstdio>

#include "mavlink_all.h"
#include "mission_frames.h"

namespace microhard_gs {
namespace {

__attribute__((format(printf, 1, 2))) std::string text(const char* fmt, ...) {
  char buf[96];
  va_list args;
  va_start(args, fmt);
  std::vsnprintf(buf, sizeof buf, fmt, args);
  va_end(args);
  return std::string(buf);
}

MissionVerdict verdict(uint8_t result, std::string reason) {
  MissionVerdict v;
  v.result = result;
  v.reason = std::move(reason);
  return v;
}

}  // namespace

bool is_home_row(const MissionItem& item, const GeoPoint& home, const MissionLimits& limits) {
  double height_ft = 0.0;
  return item.seq == 0 && item.command == MAV_CMD_NAV_WAYPOINT && is_global_frame(item.frame) &&
         height_above_home_ft(item.frame, item.z, home, &height_ft) && height_ft < limits.floor_ft;
}

MissionVerdict check_mission_item(const MissionItem& item, const GeoPoint& home,
                                  const MissionLimits& limits) {
  const int n = item.seq;
  if (item.command == MAV_CMD_DO_CHANGE_SPEED) {
    const double speed_ftps = static_cast<double>(item.param2) * kFeetPerMetre;
    if (!std::isfinite(item.param2)) {
      return verdict(MAV_MISSION_INVALID_PARAM2, text("Item %d: speed not a number", n));
    }
    // -1 (or any non-positive value) means "no change" in the MAVLink definition.
    if (item.param2 > 0.0f && speed_ftps < limits.min_speed_ftps) {
      return verdict(MAV_MISSION_INVALID_PARAM2,
                     text("Item %d: speed %.0f ft/s below stall %.0f ft/s", n, speed_ftps,
                          limits.min_speed_ftps));
    }
    return verdict(MAV_MISSION_ACCEPTED, "");
  }
  if (item.command != MAV_CMD_NAV_WAYPOINT) {
    return verdict(MAV_MISSION_UNSUPPORTED,
                   text("Item %d: command %u not supported", n, item.command));
  }
  if (!is_global_frame(item.frame)) {
    return verdict(MAV_MISSION_UNSUPPORTED_FRAME,
                   text("Item %d: frame %u not supported", n, item.frame));
  }
  const double lat_deg = item.x * 1e-7;
  const double lon_deg = item.y * 1e-7;
  if (lat_deg < -90.0 || lat_deg > 90.0) {
    return verdict(MAV_MISSION_INVALID_PARAM5_X,
                   text("Item %d: latitude %.1f invalid", n, lat_deg));
  }
  if (lon_deg < -180.0 || lon_deg > 180.0) {
    return verdict(MAV_MISSION_INVALID_PARAM6_Y,
                   text("Item %d: longitude %.1f invalid", n, lon_deg));
  }
  double height_ft = 0.0;
  if (!height_above_home_ft(item.frame, item.z, home, &height_ft)) {
    return verdict(MAV_MISSION_INVALID_PARAM7, text("Item %d: altitude invalid", n));
  }
  const bool home_row = is_home_row(item, home, limits);
  if (height_ft > limits.ceiling_ft) {
    return verdict(MAV_MISSION_INVALID_PARAM7,
                   text("Item %d: %.0f ft above ceiling %.0f ft", n, height_ft, limits.ceiling_ft));
  }
  if (height_ft < limits.floor_ft && !home_row) {
    return verdict(MAV_MISSION_INVALID_PARAM7,
                   text("Item %d: %.0f ft below floor %.0f ft", n, height_ft, limits.floor_ft));
  }
  const NorthEastFt ne = geodetic_to_north_east_ft(home, lat_deg, lon_deg);
  const double range_ft = std::hypot(ne.north_ft, ne.east_ft);
  if (range_ft > limits.max_radius_ft) {
    return verdict(MAV_MISSION_INVALID_PARAM5_X, text("Item %d: %.0f ft from home, max %.0f ft", n,
                                                      range_ft, limits.max_radius_ft));
  }
  return verdict(MAV_MISSION_ACCEPTED, "");
}

MissionVerdict build_way_plan(const MissionItem* items, int count, const GeoPoint& home,
                              const MissionLimits& limits, WayPlan* plan) {
  if (count < 0 || count > kMaxMissionItems) {
    return verdict(MAV_MISSION_NO_SPACE,
                   text("Mission of %d items, max %d", count, kMaxMissionItems));
  }
  WayPlan out;
  double speed_ftps = limits.default_speed_ftps;
  for (int i = 0; i < count; ++i) {
    const MissionVerdict v = check_mission_item(items[i], home, limits);
    if (!v.ok()) return v;
    if (items[i].command == MAV_CMD_DO_CHANGE_SPEED) {
      if (items[i].param2 > 0.0f) speed_ftps = static_cast<double>(items[i].param2) * kFeetPerMetre;
      continue;
    }
    if (is_home_row(items[i], home, limits)) continue;  // home: not flown
    double height_ft = 0.0;
    height_above_home_ft(items[i].frame, items[i].z, home, &height_ft);
    const NorthEastFt ne = geodetic_to_north_east_ft(home, items[i].x * 1e-7, items[i].y * 1e-7);
    out.north_ft[out.fp] = ne.north_ft;
    out.east_ft[out.fp] = ne.east_ft;
    out.height_ft[out.fp] = height_ft;
    out.velocity_ftps[out.fp] = speed_ftps;
    out.item_seq[out.fp] = items[i].seq;
    ++out.fp;
  }
  *plan = out;
  return verdict(MAV_MISSION_ACCEPTED, "");
}

}  // namespace microhard_gs
