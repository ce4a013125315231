#include "mission_frames.h"

#include <algorithm>
#include <cmath>

namespace microhard_gs {
namespace {

int32_t degrees_to_e7(double deg) {
  if (!std::isfinite(deg)) return INT32_MAX;  // out of range: the item check refuses it
  return static_cast<int32_t>(
      std::max(-2147483647.0, std::min(2147483647.0, std::round(deg * 1e7))));
}

int32_t to_i32(float v) {
  if (!std::isfinite(v)) return 0;
  return static_cast<int32_t>(std::max(-2147483647.0f, std::min(2147483647.0f, std::round(v))));
}

uint8_t float_twin(uint8_t frame) {
  if (frame == MAV_FRAME_GLOBAL_INT) return MAV_FRAME_GLOBAL;
  if (frame == MAV_FRAME_GLOBAL_RELATIVE_ALT_INT) return MAV_FRAME_GLOBAL_RELATIVE_ALT;
  return frame;
}

}  // namespace

bool is_global_frame(uint8_t frame) {
  return frame == MAV_FRAME_GLOBAL || frame == MAV_FRAME_GLOBAL_RELATIVE_ALT ||
         frame == MAV_FRAME_GLOBAL_INT || frame == MAV_FRAME_GLOBAL_RELATIVE_ALT_INT;
}

bool height_above_home_ft(uint8_t frame, float z_m, const GeoPoint& home, double* height_ft) {
  if (!std::isfinite(z_m)) return false;
  if (frame == MAV_FRAME_GLOBAL_RELATIVE_ALT || frame == MAV_FRAME_GLOBAL_RELATIVE_ALT_INT) {
    *height_ft = static_cast<double>(z_m) * kFeetPerMetre;
    return true;
  }
  if (frame == MAV_FRAME_GLOBAL || frame == MAV_FRAME_GLOBAL_INT) {
    *height_ft = (static_cast<double>(z_m) - home.alt_m) * kFeetPerMetre;
    return true;
  }
  return false;
}

// The fields both item messages carry alike; only x/y (x1e7 or degrees) differ.
template <typename Item>
MissionItem common_fields(const Item& m) {
  MissionItem it;
  it.seq = m.seq;
  it.frame = m.frame;
  it.command = m.command;
  it.current = m.current;
  it.autocontinue = m.autocontinue;
  it.param1 = m.param1;
  it.param2 = m.param2;
  it.param3 = m.param3;
  it.param4 = m.param4;
  return it;
}

MissionItem from_item_int(const mavlink_mission_item_int_t& m) {
  MissionItem it = common_fields(m);
  it.x = m.x;
  it.y = m.y;
  it.z = m.z;
  return it;
}

MissionItem from_item_float(const mavlink_mission_item_t& m) {
  MissionItem it = common_fields(m);
  if (is_global_frame(m.frame)) {
    it.x = degrees_to_e7(static_cast<double>(m.x));
    it.y = degrees_to_e7(static_cast<double>(m.y));
  } else {
    it.x = to_i32(m.x);
    it.y = to_i32(m.y);
  }
  it.z = m.z;
  return it;
}

mavlink_mission_item_int_t to_item_int(const MissionItem& it) {
  mavlink_mission_item_int_t m{};
  m.seq = it.seq;
  m.frame = it.frame;
  m.command = it.command;
  m.current = it.current;
  m.autocontinue = it.autocontinue;
  m.param1 = it.param1;
  m.param2 = it.param2;
  m.param3 = it.param3;
  m.param4 = it.param4;
  m.x = it.x;
  m.y = it.y;
  m.z = it.z;
  m.mission_type = MAV_MISSION_TYPE_MISSION;
  return m;
}

mavlink_mission_item_t to_item_float(const MissionItem& it) {
  mavlink_mission_item_t m{};
  const bool global = is_global_frame(it.frame);
  m.seq = it.seq;
  m.frame = float_twin(it.frame);
  m.command = it.command;
  m.current = it.current;
  m.autocontinue = it.autocontinue;
  m.param1 = it.param1;
  m.param2 = it.param2;
  m.param3 = it.param3;
  m.param4 = it.param4;
  m.x = global ? static_cast<float>(it.x * 1e-7) : static_cast<float>(it.x);
  m.y = global ? static_cast<float>(it.y * 1e-7) : static_cast<float>(it.y);
  m.z = it.z;
  m.mission_type = MAV_MISSION_TYPE_MISSION;
  return m;
}

}  // namespace microhard_gs
