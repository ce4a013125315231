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

// The fields MissionItem and both item messages carry alike, either way; x and y differ (x1e7
// or degrees), and z is the same float in all three.
template <typename From, typename To>
void copy_common_fields(const From& from, To* to) {
  to->seq = from.seq;
  to->frame = from.frame;
  to->command = from.command;
  to->current = from.current;
  to->autocontinue = from.autocontinue;
  to->param1 = from.param1;
  to->param2 = from.param2;
  to->param3 = from.param3;
  to->param4 = from.param4;
  to->z = from.z;
}

MissionItem from_item_int(const mavlink_mission_item_int_t& m) {
  MissionItem it;
  copy_common_fields(m, &it);
  it.x = m.x;
  it.y = m.y;
  return it;
}

MissionItem from_item_float(const mavlink_mission_item_t& m) {
  MissionItem it;
  copy_common_fields(m, &it);
  if (is_global_frame(m.frame)) {
    it.x = degrees_to_e7(static_cast<double>(m.x));
    it.y = degrees_to_e7(static_cast<double>(m.y));
  } else {
    it.x = to_i32(m.x);
    it.y = to_i32(m.y);
  }
  return it;
}

mavlink_mission_item_int_t to_item_int(const MissionItem& it) {
  mavlink_mission_item_int_t m{};
  copy_common_fields(it, &m);
  m.x = it.x;
  m.y = it.y;
  m.mission_type = MAV_MISSION_TYPE_MISSION;
  return m;
}

mavlink_mission_item_t to_item_float(const MissionItem& it) {
  mavlink_mission_item_t m{};
  const bool global = is_global_frame(it.frame);
  copy_common_fields(it, &m);
  m.frame = float_twin(it.frame);
  m.x = global ? static_cast<float>(it.x * 1e-7) : static_cast<float>(it.x);
  m.y = global ? static_cast<float>(it.y * 1e-7) : static_cast<float>(it.y);
  m.mission_type = MAV_MISSION_TYPE_MISSION;
  return m;
}

}  // namespace microhard_gs
