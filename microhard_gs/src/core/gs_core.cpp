#include "gs_core.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace microhard_gs {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr uint64_t kHeartbeatPeriodMs = 1000;
constexpr uint64_t kTelemetryStaleMs = 2000;  // stop claiming a position after this silence
// How long after finishing an upload a repeated last item still gets its MISSION_ACK again.
constexpr uint64_t kReAckWindowMs = 10000;
// MAVLink 2 signing timestamps count 10 us units since 2015-01-01T00:00:00Z.
constexpr uint64_t kSigningEpochUnixUs = 1420070400ULL * 1000000ULL;
// A GCS (or a flood) can ask faster than the controller answers; more than this many waiting
// are refused at once rather than queued without bound.
constexpr size_t kMaxPendingParamSets = 16;

// Messages that only read: accepted unsigned even when signing is on, so a GCS can still see
// the vehicle, its parameters and its mission. Everything else changes something and must be
// signed with the key.
bool accept_unsigned(const mavlink_status_t*, uint32_t msgid) {
  switch (msgid) {
    case MAVLINK_MSG_ID_HEARTBEAT:
    case MAVLINK_MSG_ID_SYSTEM_TIME:
    case MAVLINK_MSG_ID_PING:
    case MAVLINK_MSG_ID_PARAM_REQUEST_READ:
    case MAVLINK_MSG_ID_PARAM_REQUEST_LIST:
    case MAVLINK_MSG_ID_MISSION_REQUEST:
    case MAVLINK_MSG_ID_MISSION_REQUEST_LIST:
    case MAVLINK_MSG_ID_MISSION_REQUEST_INT:
    case MAVLINK_MSG_ID_MISSION_ACK:
    case MAVLINK_MSG_ID_TIMESYNC:
    case MAVLINK_MSG_ID_RADIO_STATUS:
      return true;
    default:
      return false;
  }
}

int32_t clamp_i32(double v) {
  if (!std::isfinite(v)) return 0;
  return static_cast<int32_t>(std::max(-2147483647.0, std::min(2147483647.0, std::round(v))));
}
int16_t clamp_i16(double v) {
  if (!std::isfinite(v)) return 0;
  return static_cast<int16_t>(std::max(-32767.0, std::min(32767.0, std::round(v))));
}
uint16_t clamp_u16(double v) {
  if (!std::isfinite(v) || v < 0.0) return 0;
  return static_cast<uint16_t>(std::min(65534.0, std::round(v)));
}
float finite_or_zero(double v) { return std::isfinite(v) ? static_cast<float>(v) : 0.0f; }

double heading_deg(double yaw_rad) {
  double h = std::fmod(yaw_rad * 180.0 / kPi, 360.0);
  if (h < 0.0) h += 360.0;
  return std::isfinite(h) ? h : 0.0;
}

}  // namespace

std::string reason_names(uint32_t reasons) {
  static const char* const kNames[] = {
      "NO_COMMAND", "DEADLINE_MISS", "NOT_FINITE", "ACTUATOR_REGION", "ALPHA_BETA",
      "SENSOR_LINK", "STALL", "CEILING", "STATE_REGION", "FROZEN",
      "INTEGRITY", "ESTIMATOR", "GROUND_COMMAND", "NO_HA_STATE"};
  std::string out;
  for (uint32_t bit = 0; bit < 32; ++bit) {
    if ((reasons & (1u << bit)) == 0) continue;
    if (!out.empty()) out += ",";
    if (bit < sizeof kNames / sizeof kNames[0]) {
      out += kNames[bit];
    } else {
      out += "BIT" + std::to_string(bit);
    }
  }
  return out;
}

GsCore::GsCore(const GsConfig& config, const ParamTable& params) : config_(config), params_(params) {
  if (config_.signing) {
    std::memcpy(signing_.secret_key, config_.signing_key.data(), sizeof signing_.secret_key);
    signing_.link_id = config_.signing_link_id;
    signing_.flags = MAVLINK_SIGNING_FLAG_SIGN_OUTGOING;
    signing_.accept_unsigned_callback = accept_unsigned;
    rx_status_.signing = &signing_;
    rx_status_.signing_streams = &signing_streams_;
    tx_status_.signing = &signing_;
    tx_status_.signing_streams = &signing_streams_;
  }
  if (config_.home_fixed) {
    home_ = config_.home;
    home_known_ = true;
  }
}

template <typename Encode>
void GsCore::emit(Encode encode) {
  mavlink_message_t msg;
  encode(&msg);
  uint8_t buf[MAVLINK_MAX_PACKET_LEN];
  const uint16_t n = mavlink_msg_to_send_buffer(buf, &msg);
  frames_.emplace_back(buf, buf + n);
}

void GsCore::update_signing_clock(const Clock& now) {
  if (!config_.signing || now.unix_us < kSigningEpochUnixUs) return;
  const uint64_t ts = (now.unix_us - kSigningEpochUnixUs) / 10;
  if (ts > signing_.timestamp) signing_.timestamp = ts;
}

void GsCore::handle_bytes(const uint8_t* data, size_t len, const Clock& now) {
  update_signing_clock(now);
  for (size_t i = 0; i < len; ++i) {
    mavlink_message_t msg;
    mavlink_status_t status;
    const uint8_t r = mavlink_frame_char_buffer(&rx_buffer_, &rx_status_, data[i], &msg, &status);
    if (r == MAVLINK_FRAMING_OK) {
      ++counters_.frames_ok;
      dispatch(msg, now);
    } else if (r == MAVLINK_FRAMING_BAD_CRC) {
      ++counters_.frames_bad_crc;
    } else if (r == MAVLINK_FRAMING_BAD_SIGNATURE) {
      if (msg.incompat_flags & MAVLINK_IFLAG_SIGNED) {
        ++counters_.refused_bad_signature;
      } else {
        ++counters_.refused_unsigned;
      }
      // An unsigned command still gets an answer, so the operator learns why nothing happened.
      if (msg.msgid == MAVLINK_MSG_ID_COMMAND_LONG) {
        mavlink_command_long_t c;
        mavlink_msg_command_long_decode(&msg, &c);
        if (c.target_system == config_.system_id) send_command_ack(msg, c.command, MAV_RESULT_DENIED);
      } else if (msg.msgid == MAVLINK_MSG_ID_COMMAND_INT) {
        mavlink_command_int_t c;
        mavlink_msg_command_int_decode(&msg, &c);
        if (c.target_system == config_.system_id) send_command_ack(msg, c.command, MAV_RESULT_DENIED);
      }
    }
  }
}

bool GsCore::addressed_to_us(uint8_t target_system, uint8_t target_component) {
  const bool ok = (target_system == 0 || target_system == config_.system_id) &&
                  (target_component == 0 || target_component == config_.component_id);
  if (!ok) ++counters_.ignored_other_target;
  return ok;
}

void GsCore::dispatch(const mavlink_message_t& msg, const Clock& now) {
  switch (msg.msgid) {
    case MAVLINK_MSG_ID_PARAM_REQUEST_LIST: {
      mavlink_param_request_list_t m;
      mavlink_msg_param_request_list_decode(&msg, &m);
      if (addressed_to_us(m.target_system, m.target_component)) on_param_request_list();
      break;
    }
    case MAVLINK_MSG_ID_PARAM_REQUEST_READ: on_param_request_read(msg); break;
    case MAVLINK_MSG_ID_PARAM_SET: on_param_set(msg, now); break;
    case MAVLINK_MSG_ID_MISSION_COUNT: on_mission_count(msg, now); break;
    case MAVLINK_MSG_ID_MISSION_ITEM_INT: {
      mavlink_mission_item_int_t m;
      mavlink_msg_mission_item_int_decode(&msg, &m);
      on_mission_item(msg, from_item_int(m), m.target_system, m.target_component, m.mission_type,
                      false, now);
      break;
    }
    case MAVLINK_MSG_ID_MISSION_ITEM: {
      mavlink_mission_item_t m;
      mavlink_msg_mission_item_decode(&msg, &m);
      on_mission_item(msg, from_item_float(m), m.target_system, m.target_component, m.mission_type,
                      true, now);
      break;
    }
    case MAVLINK_MSG_ID_MISSION_REQUEST_LIST: on_mission_request_list(msg); break;
    case MAVLINK_MSG_ID_MISSION_REQUEST_INT: on_mission_request(msg, false); break;
    case MAVLINK_MSG_ID_MISSION_REQUEST: on_mission_request(msg, true); break;
    case MAVLINK_MSG_ID_MISSION_CLEAR_ALL: on_mission_clear_all(msg); break;
    case MAVLINK_MSG_ID_MISSION_ACK: on_mission_ack(msg); break;
    case MAVLINK_MSG_ID_COMMAND_LONG: {
      mavlink_command_long_t c;
      mavlink_msg_command_long_decode(&msg, &c);
      const float p[7] = {c.param1, c.param2, c.param3, c.param4, c.param5, c.param6, c.param7};
      on_command(msg, c.command, p, c.target_system, c.target_component);
      break;
    }
    case MAVLINK_MSG_ID_COMMAND_INT: {
      mavlink_command_int_t c;
      mavlink_msg_command_int_decode(&msg, &c);
      const float p[7] = {c.param1, c.param2, c.param3, c.param4, static_cast<float>(c.x),
                          static_cast<float>(c.y), c.z};
      command_int_ = true;
      command_int_x_ = c.x;
      command_int_y_ = c.y;
      on_command(msg, c.command, p, c.target_system, c.target_component);
      command_int_ = false;
      break;
    }
    default:
      break;  // not for us (GCS heartbeats, radio status, ...)
  }
}

// ---------------------------------------------------------------- parameters

void GsCore::send_param(size_t index) {
  const ParamTable::Entry& e = params_.at(index);
  mavlink_param_value_t pv{};
  // param_id is 16 characters, terminated only when shorter (ids are checked <= 16 at build).
  std::memcpy(pv.param_id, e.mav_id.data(), std::min(e.mav_id.size(), sizeof pv.param_id));
  if (e.is_integer) {
    // Byte-wise encoding (advertised in AUTOPILOT_VERSION): the int32's bytes travel in the float.
    const int32_t v = static_cast<int32_t>(e.value);
    float f;
    std::memcpy(&f, &v, sizeof f);
    pv.param_value = f;
    pv.param_type = MAV_PARAM_TYPE_INT32;
  } else {
    pv.param_value = static_cast<float>(e.value);
    pv.param_type = MAV_PARAM_TYPE_REAL32;
  }
  pv.param_count = static_cast<uint16_t>(params_.size());
  pv.param_index = static_cast<uint16_t>(index);
  emit([&](mavlink_message_t* m) {
    mavlink_msg_param_value_encode_status(config_.system_id, config_.component_id, &tx_status_, m, &pv);
  });
}

void GsCore::on_param_request_list() {
  for (size_t i = 0; i < params_.size(); ++i) send_param(i);
}

void GsCore::on_param_request_read(const mavlink_message_t& msg) {
  mavlink_param_request_read_t m;
  mavlink_msg_param_request_read_decode(&msg, &m);
  if (!addressed_to_us(m.target_system, m.target_component)) return;
  int index = m.param_index;
  if (index < 0) {
    char id[sizeof m.param_id];
    std::memcpy(id, m.param_id, sizeof id);
    index = params_.find(id, sizeof id);
  }
  if (index >= 0 && static_cast<size_t>(index) < params_.size()) send_param(static_cast<size_t>(index));
}

void GsCore::on_param_set(const mavlink_message_t& msg, const Clock& now) {
  mavlink_param_set_t m;
  mavlink_msg_param_set_decode(&msg, &m);
  if (!addressed_to_us(m.target_system, m.target_component)) return;
  char id[sizeof m.param_id];
  std::memcpy(id, m.param_id, sizeof id);
  const int index = params_.find(id, sizeof id);
  if (index < 0) return;  // the protocol has no negative answer: the GCS times out
  const size_t i = static_cast<size_t>(index);
  double value = m.param_value;
  if (params_.at(i).is_integer && m.param_type != MAV_PARAM_TYPE_REAL32) {
    // Byte-wise encoding: the int32's bytes travel in the float. A REAL32-typed set of an
    // integer goes as it is; the controller refuses it unless whole.
    int32_t v;
    const float f = m.param_value;
    std::memcpy(&v, &f, sizeof v);
    value = v;
  }
  if (pending_param_sets_.size() >= kMaxPendingParamSets) {
    refuse_param_set(i, "busy, too many sets waiting for the controller");
    return;
  }
  // No echo yet: the echo is the value in force, and only the controller knows it. Its range
  // checks are the ones its parameter files meet (one limit, one place).
  ParamSetRequest r;
  r.id = ++next_param_set_id_;
  r.ros_name = params_.at(i).ros_name;
  r.value = value;
  param_set_requests_.push_back(r);
  pending_param_sets_.push_back(PendingParamSet{r.id, i, now.mono_ms});
}

void GsCore::refuse_param_set(size_t index, const std::string& reason) {
  ++counters_.param_sets_refused;
  send_param(index);  // the old value: how MAVLink tells a GCS that the set did not happen
  send_statustext(MAV_SEVERITY_WARNING, "Param " + params_.at(index).mav_id + " refused: " + reason);
}

void GsCore::param_set_answered(const ParamSetRequest& request, const ParamSetAnswer& answer) {
  const auto it = std::find_if(pending_param_sets_.begin(), pending_param_sets_.end(),
                               [&](const PendingParamSet& p) { return p.id == request.id; });
  if (it == pending_param_sets_.end()) {
    // Too late: the GCS was told the set failed. Only a change that did happen needs telling.
    const int index = params_.find_ros_name(request.ros_name);
    if (!answer.accepted || index < 0) return;
    const size_t i = static_cast<size_t>(index);
    params_.store(i, answer.value_in_force);
    ++counters_.param_sets_accepted;
    send_param(i);
    send_statustext(MAV_SEVERITY_NOTICE, "Param " + params_.at(i).mav_id + " set after all (late answer)");
    return;
  }
  const size_t i = it->index;
  pending_param_sets_.erase(it);
  if (!answer.accepted) {
    refuse_param_set(i, answer.reason.empty() ? std::string("no reason given") : answer.reason);
    return;
  }
  params_.store(i, answer.value_in_force);
  ++counters_.param_sets_accepted;
  send_param(i);
}

// ---------------------------------------------------------------- missions

void GsCore::send_mission_ack(uint8_t sys, uint8_t comp, uint8_t result, uint8_t mission_type) {
  mavlink_mission_ack_t a{};
  a.target_system = sys;
  a.target_component = comp;
  a.type = result;
  a.mission_type = mission_type;
  emit([&](mavlink_message_t* m) {
    mavlink_msg_mission_ack_encode_status(config_.system_id, config_.component_id, &tx_status_, m, &a);
  });
}

void GsCore::on_mission_count(const mavlink_message_t& msg, const Clock& now) {
  mavlink_mission_count_t m;
  mavlink_msg_mission_count_decode(&msg, &m);
  if (!addressed_to_us(m.target_system, m.target_component)) return;
  if (m.mission_type != MAV_MISSION_TYPE_MISSION) {
    // No geofence or rally points on this vehicle.
    send_mission_ack(msg.sysid, msg.compid, MAV_MISSION_UNSUPPORTED, m.mission_type);
    return;
  }
  if (m.count > kMaxMissionItems) {
    ++counters_.missions_rejected;
    upload_.active = false;
    const std::string why = "Mission rejected: " + std::to_string(m.count) + " items, max " +
                            std::to_string(kMaxMissionItems);
    send_mission_ack(msg.sysid, msg.compid, MAV_MISSION_NO_SPACE, MAV_MISSION_TYPE_MISSION);
    send_statustext(MAV_SEVERITY_WARNING, why);
    return;
  }
  if (m.count == 0) {  // an empty upload clears the mission
    upload_.active = false;
    mission_count_ = 0;
    mission_plan_ = WayPlan{};
    way_plans_.push_back(WayPlan{});
    ++counters_.missions_accepted;
    send_mission_ack(msg.sysid, msg.compid, MAV_MISSION_ACCEPTED, MAV_MISSION_TYPE_MISSION);
    return;
  }
  // A repeated MISSION_COUNT (our first request was lost) simply restarts the transfer.
  upload_ = Upload{};
  upload_.active = true;
  upload_.partner_sys = msg.sysid;
  upload_.partner_comp = msg.compid;
  upload_.count = m.count;
  upload_.next_seq = 0;
  last_upload_.valid = false;
  request_next_item(now);
}

void GsCore::request_next_item(const Clock& now) {
  const uint16_t seq = static_cast<uint16_t>(upload_.next_seq);
  if (upload_.legacy) {
    mavlink_mission_request_t r{};
    r.target_system = upload_.partner_sys;
    r.target_component = upload_.partner_comp;
    r.seq = seq;
    r.mission_type = MAV_MISSION_TYPE_MISSION;
    emit([&](mavlink_message_t* m) {
      mavlink_msg_mission_request_encode_status(config_.system_id, config_.component_id, &tx_status_, m, &r);
    });
  } else {
    mavlink_mission_request_int_t r{};
    r.target_system = upload_.partner_sys;
    r.target_component = upload_.partner_comp;
    r.seq = seq;
    r.mission_type = MAV_MISSION_TYPE_MISSION;
    emit([&](mavlink_message_t* m) {
      mavlink_msg_mission_request_int_encode_status(config_.system_id, config_.component_id, &tx_status_, m, &r);
    });
  }
  upload_.last_request_ms = now.mono_ms;
}

void GsCore::finish_upload(uint8_t result, const std::string& reason, const Clock& now) {
  send_mission_ack(upload_.partner_sys, upload_.partner_comp, result, MAV_MISSION_TYPE_MISSION);
  if (result != MAV_MISSION_ACCEPTED) {
    ++counters_.missions_rejected;
    send_statustext(MAV_SEVERITY_WARNING, "Mission rejected: " + reason);
  }
  last_upload_.valid = true;
  last_upload_.partner_sys = upload_.partner_sys;
  last_upload_.partner_comp = upload_.partner_comp;
  last_upload_.last_seq = upload_.next_seq;
  last_upload_.result = result;
  last_upload_.finished_ms = now.mono_ms;
  upload_.active = false;
}

void GsCore::on_mission_item(const mavlink_message_t& msg, const MissionItem& item, uint8_t target_sys,
                             uint8_t target_comp, uint8_t mission_type, bool legacy, const Clock& now) {
  if (!addressed_to_us(target_sys, target_comp) || mission_type != MAV_MISSION_TYPE_MISSION) return;
  if (!upload_.active || msg.sysid != upload_.partner_sys || msg.compid != upload_.partner_comp) {
    // The GCS repeats the last item when our final MISSION_ACK was lost: answer it again.
    if (last_upload_.valid && msg.sysid == last_upload_.partner_sys &&
        msg.compid == last_upload_.partner_comp && item.seq == last_upload_.last_seq &&
        now.mono_ms - last_upload_.finished_ms < kReAckWindowMs) {
      send_mission_ack(msg.sysid, msg.compid, last_upload_.result, MAV_MISSION_TYPE_MISSION);
    }
    return;
  }
  if (legacy) upload_.legacy = true;
  upload_.answered = true;
  if (item.seq != upload_.next_seq) {
    // A duplicate of an item already stored, or one from the future: ask again for the one
    // we need (the protocol's answer to out-of-sequence items).
    request_next_item(now);
    return;
  }
  upload_.retries = 0;
  const MissionVerdict v = home_known_ ? check_mission_item(item, home_, config_.limits)
                                       : MissionVerdict{MAV_MISSION_DENIED, "no home position yet"};
  if (!v.ok()) {
    finish_upload(v.result, v.reason, now);
    return;
  }
  upload_.items[upload_.next_seq] = item;
  if (upload_.next_seq + 1 < upload_.count) {
    ++upload_.next_seq;
    request_next_item(now);
    return;
  }
  WayPlan plan;
  const MissionVerdict all = build_way_plan(upload_.items, upload_.count, home_, config_.limits, &plan);
  if (!all.ok()) {
    finish_upload(all.result, all.reason, now);
    return;
  }
  std::copy(upload_.items, upload_.items + upload_.count, mission_);
  mission_count_ = upload_.count;
  mission_plan_ = plan;
  way_plans_.push_back(plan);
  ++counters_.missions_accepted;
  finish_upload(MAV_MISSION_ACCEPTED, "", now);
  const bool home_row = is_home_row(mission_[0], home_, config_.limits);
  send_statustext(MAV_SEVERITY_INFO, "Mission accepted: " + std::to_string(plan.fp) + " waypoints" +
                                         (home_row ? ", item 0 is home (not flown)" : ""));
}

void GsCore::on_mission_request_list(const mavlink_message_t& msg) {
  mavlink_mission_request_list_t m;
  mavlink_msg_mission_request_list_decode(&msg, &m);
  if (!addressed_to_us(m.target_system, m.target_component)) return;
  mavlink_mission_count_t c{};
  c.target_system = msg.sysid;
  c.target_component = msg.compid;
  c.count = m.mission_type == MAV_MISSION_TYPE_MISSION ? static_cast<uint16_t>(mission_count_) : 0;
  c.mission_type = m.mission_type;
  emit([&](mavlink_message_t* out) {
    mavlink_msg_mission_count_encode_status(config_.system_id, config_.component_id, &tx_status_, out, &c);
  });
}

void GsCore::on_mission_request(const mavlink_message_t& msg, bool legacy) {
  uint16_t seq = 0;
  uint8_t mission_type = 0;
  if (legacy) {
    mavlink_mission_request_t r;
    mavlink_msg_mission_request_decode(&msg, &r);
    if (!addressed_to_us(r.target_system, r.target_component)) return;
    seq = r.seq;
    mission_type = r.mission_type;
  } else {
    mavlink_mission_request_int_t r;
    mavlink_msg_mission_request_int_decode(&msg, &r);
    if (!addressed_to_us(r.target_system, r.target_component)) return;
    seq = r.seq;
    mission_type = r.mission_type;
  }
  if (mission_type != MAV_MISSION_TYPE_MISSION || seq >= mission_count_) {
    send_mission_ack(msg.sysid, msg.compid, MAV_MISSION_INVALID_SEQUENCE, mission_type);
    return;
  }
  // Downloads answer in the frame each item was uploaded in (mission_frames.h).
  if (legacy) {
    mavlink_mission_item_t m = to_item_float(mission_[seq]);
    m.target_system = msg.sysid;
    m.target_component = msg.compid;
    m.current = seq == 0 ? 1 : 0;
    emit([&](mavlink_message_t* out) {
      mavlink_msg_mission_item_encode_status(config_.system_id, config_.component_id, &tx_status_, out, &m);
    });
  } else {
    mavlink_mission_item_int_t m = to_item_int(mission_[seq]);
    m.target_system = msg.sysid;
    m.target_component = msg.compid;
    m.current = seq == 0 ? 1 : 0;
    emit([&](mavlink_message_t* out) {
      mavlink_msg_mission_item_int_encode_status(config_.system_id, config_.component_id, &tx_status_, out, &m);
    });
  }
}

void GsCore::on_mission_clear_all(const mavlink_message_t& msg) {
  mavlink_mission_clear_all_t m;
  mavlink_msg_mission_clear_all_decode(&msg, &m);
  if (!addressed_to_us(m.target_system, m.target_component)) return;
  if (m.mission_type == MAV_MISSION_TYPE_MISSION || m.mission_type == MAV_MISSION_TYPE_ALL) {
    upload_.active = false;
    mission_count_ = 0;
    mission_plan_ = WayPlan{};
    way_plans_.push_back(WayPlan{});
  }
  send_mission_ack(msg.sysid, msg.compid, MAV_MISSION_ACCEPTED, m.mission_type);
}

void GsCore::on_mission_ack(const mavlink_message_t& msg) {
  mavlink_mission_ack_t a;
  mavlink_msg_mission_ack_decode(&msg, &a);
  // The GCS gives up on an upload: drop it, the stored mission is untouched.
  if (upload_.active && msg.sysid == upload_.partner_sys && a.type != MAV_MISSION_ACCEPTED &&
      a.mission_type == MAV_MISSION_TYPE_MISSION) {
    upload_.active = false;
  }
}

// ---------------------------------------------------------------- commands

void GsCore::send_command_ack(const mavlink_message_t& msg, uint16_t command, uint8_t result) {
  mavlink_command_ack_t a{};
  a.command = command;
  a.result = result;
  a.target_system = msg.sysid;
  a.target_component = msg.compid;
  emit([&](mavlink_message_t* m) {
    mavlink_msg_command_ack_encode_status(config_.system_id, config_.component_id, &tx_status_, m, &a);
  });
}

void GsCore::on_command(const mavlink_message_t& msg, uint16_t command, const float params[7],
                        uint8_t target_sys, uint8_t target_comp) {
  if (!addressed_to_us(target_sys, target_comp)) return;
  const uint8_t result = execute_command(command, params);
  if (result == MAV_RESULT_ACCEPTED) {
    ++counters_.commands_accepted;
  } else {
    ++counters_.commands_refused;
  }
  send_command_ack(msg, command, result);
  // Answers that follow the ACK (the requested message itself).
  if (result == MAV_RESULT_ACCEPTED) {
    const bool want_version = command == MAV_CMD_REQUEST_AUTOPILOT_CAPABILITIES ||
                              (command == MAV_CMD_REQUEST_MESSAGE &&
                               params[0] == static_cast<float>(MAVLINK_MSG_ID_AUTOPILOT_VERSION));
    const bool want_home = command == MAV_CMD_GET_HOME_POSITION ||
                           (command == MAV_CMD_REQUEST_MESSAGE &&
                            params[0] == static_cast<float>(MAVLINK_MSG_ID_HOME_POSITION));
    if (want_version) send_autopilot_version();
    if (want_home) send_home_position();
    const bool request = command == MAV_CMD_REQUEST_MESSAGE;
    if (request && params[0] == static_cast<float>(MAVLINK_MSG_ID_CURRENT_MODE)) send_current_mode();
    if (request && params[0] == static_cast<float>(MAVLINK_MSG_ID_AVAILABLE_MODES)) {
      const int index = static_cast<int>(params[1]);
      for (int i = index == 0 ? 1 : index; i <= (index == 0 ? kModeCount : index); ++i) send_available_mode(i);
    }
  }
}

// The MAV_CMDs this vehicle understands (documented in microhard_gs/README.md):
//   DO_SET_MODE, param1 with CUSTOM_MODE_ENABLED, param2 = 0 -> SELECT_HP, 1 -> SELECT_HA
//   PREFLIGHT_REBOOT_SHUTDOWN, param1 = 0 (the HA is never rebooted from the ground),
//     param2 = 1 (reboot the onboard computer) -> RESTART_HP
//   ACTUATOR_TEST -> SELF_TEST (the HA's whole surface self-test; refused while airborne)
//   REQUEST_MESSAGE (AUTOPILOT_VERSION, HOME_POSITION), REQUEST_AUTOPILOT_CAPABILITIES,
//   GET_HOME_POSITION
//   DO_SET_HOME -> SET_HOME (on the ground only; gs_home.cpp)
// ACCEPTED for an operator request means "forwarded to the HA": the HA's checks still decide.
uint8_t GsCore::execute_command(uint16_t command, const float params[7]) {
  switch (command) {
    case MAV_CMD_DO_SET_MODE: {
      if (!std::isfinite(params[0]) || !std::isfinite(params[1])) return MAV_RESULT_DENIED;
      const uint32_t flags = static_cast<uint32_t>(params[0]);
      if ((flags & MAV_MODE_FLAG_CUSTOM_MODE_ENABLED) == 0) return MAV_RESULT_DENIED;
      if (params[1] == 0.0f || params[1] == 1.0f) {
        operator_requests_.push_back(params[1] == 0.0f ? OperatorRequest::kSelectHp : OperatorRequest::kSelectHa);
        intended_custom_mode_ = params[1] == 0.0f ? kControllerHp : kControllerHa;
        return MAV_RESULT_ACCEPTED;
      }
      return MAV_RESULT_DENIED;
    }
    case MAV_CMD_PREFLIGHT_REBOOT_SHUTDOWN:
      if (params[0] == 0.0f && params[1] == 1.0f) {
        operator_requests_.push_back(OperatorRequest::kRestartHp);
        return MAV_RESULT_ACCEPTED;
      }
      return MAV_RESULT_DENIED;
    case MAV_CMD_ACTUATOR_TEST:
      // The HA refuses it in the air too; refusing here first gives the operator the reason.
      if (have_decision_ && decision_.altitude_agl_ft > config_.airborne_agl_ft) {
        send_statustext(MAV_SEVERITY_WARNING, "Self-test refused: airborne");
        return MAV_RESULT_TEMPORARILY_REJECTED;
      }
      operator_requests_.push_back(OperatorRequest::kSelfTest);
      return MAV_RESULT_ACCEPTED;
    case MAV_CMD_DO_SET_HOME:
      return command_int_ ? set_home_command(params[0], command_int_x_ * 1e-7, command_int_y_ * 1e-7, params[6])
                          : set_home_command(params[0], params[4], params[5], params[6]);
    case MAV_CMD_REQUEST_AUTOPILOT_CAPABILITIES:
    case MAV_CMD_GET_HOME_POSITION:
      if (command == MAV_CMD_GET_HOME_POSITION && !home_known_) return MAV_RESULT_TEMPORARILY_REJECTED;
      return MAV_RESULT_ACCEPTED;
    case MAV_CMD_REQUEST_MESSAGE:
      if (params[0] == static_cast<float>(MAVLINK_MSG_ID_AUTOPILOT_VERSION)) return MAV_RESULT_ACCEPTED;
      if (params[0] == static_cast<float>(MAVLINK_MSG_ID_HOME_POSITION)) {
        return home_known_ ? MAV_RESULT_ACCEPTED : MAV_RESULT_TEMPORARILY_REJECTED;
      }
      if (params[0] == static_cast<float>(MAVLINK_MSG_ID_CURRENT_MODE)) return MAV_RESULT_ACCEPTED;
      if (params[0] == static_cast<float>(MAVLINK_MSG_ID_AVAILABLE_MODES)) {
        // param2: 0 for every mode, else the index of one (1-based).
        const bool one = params[1] >= 1.0f && params[1] <= static_cast<float>(kModeCount) &&
                         params[1] == std::floor(params[1]);
        return params[1] == 0.0f || one ? MAV_RESULT_ACCEPTED : MAV_RESULT_DENIED;
      }
      return MAV_RESULT_UNSUPPORTED;
    default:
      return MAV_RESULT_UNSUPPORTED;
  }
}

// ---------------------------------------------------------------- telemetry

void GsCore::set_telemetry(const Telemetry& t, const Clock& now) {
  telemetry_ = t;
  have_telemetry_ = true;
  telemetry_ms_ = now.mono_ms;
}

std::string decision_announcement(const DecisionInfo* previous, const DecisionInfo& now, uint8_t* severity) {
  const uint32_t why = now.reasons_at_switch != 0 ? now.reasons_at_switch : now.reasons;
  const std::string reasons = why != 0 ? reason_names(why) : std::string();
  std::string reason;
  switch (now.controller) {
    case kControllerHp:  // the HA hands control back only once its command stayed valid long enough
      *severity = MAV_SEVERITY_NOTICE;
      reason = "HP command stable";
      break;
    case kControllerHa:
      *severity = MAV_SEVERITY_WARNING;
      reason = reasons.empty() ? "no reason reported" : reasons;
      break;
    case kControllerRecovering:  // the HA still flies, the HP's command is valid again and on probation
      *severity = MAV_SEVERITY_NOTICE;
      reason = "HP command valid, watching its stability";
      break;
    case kControllerHaLatched:  // the HA for good: the HP was restarted as often as allowed
      *severity = MAV_SEVERITY_CRITICAL;
      reason = "restart cap reached" + (reasons.empty() ? std::string() : "; " + reasons);
      break;
    case kControllerManual:
      *severity = MAV_SEVERITY_NOTICE;
      reason = "pilot in command (PIC switch)";
      break;
    default:
      *severity = MAV_SEVERITY_WARNING;
      reason = reasons.empty() ? "no reason reported" : reasons;
      break;
  }
  if (previous != nullptr && previous->controller == kControllerManual && now.controller != kControllerManual) {
    reason = "PIC switch to computer; " + reason;
  }
  if (previous == nullptr) {
    // The first status this node sees: at boot, or mid-flight after a respawn. Either way the
    // operator has not been told who flies, nor why.
    return std::string("Controller ") + controller_name(now.controller) + " (first report): " + reason;
  }
  return std::string("Controller ") + controller_name(previous->controller) + "->" +
         controller_name(now.controller) + ": " + reason;
}

void GsCore::set_decision(const DecisionInfo& d) {
  const bool changed = !have_decision_ || d.controller != decision_.controller;
  if (changed) {
    uint8_t severity = MAV_SEVERITY_NOTICE;
    const std::string text = decision_announcement(have_decision_ ? &decision_ : nullptr, d, &severity);
    send_statustext(severity, text);
  }
  decision_ = d;
  have_decision_ = true;
  if (changed) send_current_mode();  // the standard-modes protocol wants every change at once
}

void GsCore::send_statustext(uint8_t severity, const std::string& text) {
  // MAVLink 2 splits long texts into 50-character chunks sharing a non-zero id; the last chunk
  // is shorter than 50 (so it carries the terminator), hence the "<=" below.
  const size_t kChunk = MAVLINK_MSG_STATUSTEXT_FIELD_TEXT_LEN;
  const bool multi = text.size() >= kChunk;
  uint16_t id = 0;
  if (multi) {
    ++statustext_id_;
    if (statustext_id_ == 0) statustext_id_ = 1;
    id = statustext_id_;
  }
  for (size_t off = 0, seq = 0; off <= text.size() && seq < 8; off += kChunk, ++seq) {
    mavlink_statustext_t s{};
    s.severity = severity;
    const size_t n = std::min(kChunk, text.size() - off);
    std::memcpy(s.text, text.data() + off, n);
    s.id = id;
    s.chunk_seq = static_cast<uint8_t>(seq);
    emit([&](mavlink_message_t* m) {
      mavlink_msg_statustext_encode_status(config_.system_id, config_.component_id, &tx_status_, m, &s);
    });
    if (!multi) break;
  }
}

void GsCore::send_autopilot_version() {
  mavlink_autopilot_version_t v{};
  v.capabilities = MAV_PROTOCOL_CAPABILITY_MISSION_INT | MAV_PROTOCOL_CAPABILITY_MAVLINK2 |
                   MAV_PROTOCOL_CAPABILITY_COMMAND_INT | MAV_PROTOCOL_CAPABILITY_PARAM_ENCODE_BYTEWISE;
  v.flight_sw_version = 0x00010000u;  // 0.1.0, the drone_ros package version
  v.uid = config_.system_id;
  emit([&](mavlink_message_t* m) {
    mavlink_msg_autopilot_version_encode_status(config_.system_id, config_.component_id, &tx_status_, m, &v);
  });
}

void GsCore::send_home_position() {
  if (!home_known_) return;
  mavlink_home_position_t h{};
  h.latitude = clamp_i32(home_.lat_deg * 1e7);
  h.longitude = clamp_i32(home_.lon_deg * 1e7);
  h.altitude = clamp_i32(home_.alt_m * 1000.0);
  h.q[0] = 1.0f;
  emit([&](mavlink_message_t* m) {
    mavlink_msg_home_position_encode_status(config_.system_id, config_.component_id, &tx_status_, m, &h);
  });
}

void GsCore::send_available_mode(int mode_index) {
  mavlink_available_modes_t m{};
  if (!available_mode(mode_index, &m)) return;
  emit([&](mavlink_message_t* out) {
    mavlink_msg_available_modes_encode_status(config_.system_id, config_.component_id, &tx_status_, out, &m);
  });
}

void GsCore::send_current_mode() {
  const mavlink_current_mode_t m = current_mode(have_decision_, decision_.controller, intended_custom_mode_);
  emit([&](mavlink_message_t* out) {
    mavlink_msg_current_mode_encode_status(config_.system_id, config_.component_id, &tx_status_, out, &m);
  });
}

void GsCore::send_heartbeat() {
  mavlink_heartbeat_t hb{};
  hb.type = MAV_TYPE_FIXED_WING;
  hb.autopilot = MAV_AUTOPILOT_GENERIC;
  const bool airborne = have_decision_ && decision_.altitude_agl_ft > config_.airborne_agl_ft;
  // custom_mode tells which controller drives the servos (DecisionStatus.CONTROLLER_*, modes.h).
  hb.base_mode = heartbeat_base_mode(have_decision_, decision_.controller, airborne);
  hb.custom_mode = have_decision_ ? decision_.controller : kCustomModeUnknown;
  hb.system_status = airborne ? MAV_STATE_ACTIVE : MAV_STATE_STANDBY;
  if (have_decision_ && (decision_.controller == kControllerHa || decision_.controller == kControllerHaLatched)) {
    hb.system_status = MAV_STATE_CRITICAL;  // flying on the safety controller
  }
  hb.mavlink_version = 3;
  emit([&](mavlink_message_t* m) {
    mavlink_msg_heartbeat_encode_status(config_.system_id, config_.component_id, &tx_status_, m, &hb);
  });
  send_current_mode();  // streamed with the heartbeat (the protocol asks for about 0.5 Hz)
}

void GsCore::send_telemetry_set(const Clock& now) {
  const uint32_t boot_ms = static_cast<uint32_t>(now.mono_ms - boot_ms_);
  const bool fresh = have_telemetry_ && now.mono_ms - telemetry_ms_ < kTelemetryStaleMs;
  const Telemetry& t = telemetry_;

  mavlink_sys_status_t s{};
  const uint32_t sensors = MAV_SYS_STATUS_SENSOR_3D_GYRO | MAV_SYS_STATUS_SENSOR_3D_ACCEL |
                           MAV_SYS_STATUS_SENSOR_GPS | MAV_SYS_STATUS_SENSOR_DIFFERENTIAL_PRESSURE |
                           MAV_SYS_STATUS_SENSOR_ABSOLUTE_PRESSURE;
  s.onboard_control_sensors_present = sensors;
  s.onboard_control_sensors_enabled = sensors;
  uint32_t health = 0;
  if (fresh && t.ins_link_up) health |= MAV_SYS_STATUS_SENSOR_3D_GYRO | MAV_SYS_STATUS_SENSOR_3D_ACCEL | MAV_SYS_STATUS_SENSOR_GPS;
  if (fresh && t.ha_link_up) health |= MAV_SYS_STATUS_SENSOR_DIFFERENTIAL_PRESSURE | MAV_SYS_STATUS_SENSOR_ABSOLUTE_PRESSURE;
  // No geofence: neither present nor enabled, and healthy (never breached), as ArduPilot reports
  // it. A ground station that starts out assuming the fence healthy (MAVProxy) would otherwise
  // announce "fence breach" on the first SYS_STATUS.
  s.onboard_control_sensors_health = health | MAV_SYS_STATUS_GEOFENCE;
  s.voltage_battery = fresh ? clamp_u16(t.voltage_v * 1000.0) : UINT16_MAX;
  s.current_battery = -1;
  s.battery_remaining = -1;
  s.errors_comm = clamp_u16(static_cast<double>(counters_.frames_bad_crc % 65535));
  emit([&](mavlink_message_t* m) {
    mavlink_msg_sys_status_encode_status(config_.system_id, config_.component_id, &tx_status_, m, &s);
  });
  if (!fresh) return;  // no position or attitude to claim

  mavlink_attitude_t a{};
  a.time_boot_ms = boot_ms;
  a.roll = finite_or_zero(t.roll_rad);
  a.pitch = finite_or_zero(t.pitch_rad);
  a.yaw = finite_or_zero(t.yaw_rad);
  a.rollspeed = finite_or_zero(t.p_radps);
  a.pitchspeed = finite_or_zero(t.q_radps);
  a.yawspeed = finite_or_zero(t.r_radps);
  emit([&](mavlink_message_t* m) {
    mavlink_msg_attitude_encode_status(config_.system_id, config_.component_id, &tx_status_, m, &a);
  });

  const double ground_mps = std::hypot(t.v_north_mps, t.v_east_mps);
  const double hdg_deg = heading_deg(t.yaw_rad);
  const bool position_ok = is_valid_position(t.lat_deg, t.lon_deg) && std::isfinite(t.alt_m);

  mavlink_global_position_int_t g{};
  g.time_boot_ms = boot_ms;
  g.lat = clamp_i32(t.lat_deg * 1e7);
  g.lon = clamp_i32(t.lon_deg * 1e7);
  g.alt = clamp_i32(t.alt_m * 1000.0);  // ellipsoid height: the INS gives no geoid separation
  g.relative_alt = home_known_ ? clamp_i32((t.alt_m - home_.alt_m) * 1000.0) : 0;
  g.vx = clamp_i16(t.v_north_mps * 100.0);
  g.vy = clamp_i16(t.v_east_mps * 100.0);
  g.vz = clamp_i16(t.v_down_mps * 100.0);
  g.hdg = clamp_u16(hdg_deg * 100.0);
  emit([&](mavlink_message_t* m) {
    mavlink_msg_global_position_int_encode_status(config_.system_id, config_.component_id, &tx_status_, m, &g);
  });

  mavlink_vfr_hud_t v{};
  v.airspeed = finite_or_zero(t.airspeed_ftps / kFeetPerMetre);
  v.groundspeed = finite_or_zero(ground_mps);
  v.heading = static_cast<int16_t>(hdg_deg);
  v.throttle = clamp_u16(std::max(0.0, std::min(1.0, t.throttle)) * 100.0);
  v.alt = finite_or_zero(t.alt_m);
  v.climb = finite_or_zero(-t.v_down_mps);
  emit([&](mavlink_message_t* m) {
    mavlink_msg_vfr_hud_encode_status(config_.system_id, config_.component_id, &tx_status_, m, &v);
  });

  mavlink_gps_raw_int_t r{};
  r.time_usec = static_cast<uint64_t>(boot_ms) * 1000u;
  r.fix_type = position_ok && t.ins_link_up ? GPS_FIX_TYPE_3D_FIX : GPS_FIX_TYPE_NO_FIX;
  r.lat = g.lat;
  r.lon = g.lon;
  r.alt = g.alt;
  r.eph = UINT16_MAX;
  r.epv = UINT16_MAX;
  r.vel = clamp_u16(ground_mps * 100.0);
  r.cog = clamp_u16(std::fmod(std::atan2(t.v_east_mps, t.v_north_mps) * 180.0 / kPi + 360.0, 360.0) * 100.0);
  r.satellites_visible = 255;  // unknown: /data does not carry it
  emit([&](mavlink_message_t* m) {
    mavlink_msg_gps_raw_int_encode_status(config_.system_id, config_.component_id, &tx_status_, m, &r);
  });

  send_home_position();

  if (mission_count_ > 0) {
    mavlink_mission_current_t c{};
    // The controller counts the waypoints on /way; the GCS counts mission items (home, speeds).
    const int32_t wp = std::max<int32_t>(0, std::min<int32_t>(t.waypoint_index, mission_plan_.fp - 1));
    c.seq = static_cast<uint16_t>(mission_plan_.fp > 0 ? mission_plan_.item_seq[wp] : 0);
    c.total = static_cast<uint16_t>(mission_count_);
    c.mission_state = MISSION_STATE_ACTIVE;
    c.mission_mode = t.computer_in_command ? 1 : 2;
    emit([&](mavlink_message_t* m) {
      mavlink_msg_mission_current_encode_status(config_.system_id, config_.component_id, &tx_status_, m, &c);
    });
  }
  ++counters_.telemetry_sets_sent;
}

void GsCore::tick(const Clock& now) {
  update_signing_clock(now);
  if (!started_) {
    started_ = true;
    boot_ms_ = now.mono_ms;
    next_heartbeat_ms_ = now.mono_ms;
    next_telemetry_ms_ = now.mono_ms;
  }
  if (now.mono_ms >= next_heartbeat_ms_) {
    send_heartbeat();
    next_heartbeat_ms_ += kHeartbeatPeriodMs;
    if (next_heartbeat_ms_ <= now.mono_ms) next_heartbeat_ms_ = now.mono_ms + kHeartbeatPeriodMs;
  }
  if (config_.telemetry_rate_hz > 0.0 && now.mono_ms >= next_telemetry_ms_) {
    send_telemetry_set(now);
    // Step the schedule by the period (not from now) so the rate holds without drift; after a
    // long stall, restart the schedule instead of bursting.
    const uint64_t period_ms = static_cast<uint64_t>(std::llround(1000.0 / config_.telemetry_rate_hz));
    next_telemetry_ms_ += std::max<uint64_t>(1, period_ms);
    if (next_telemetry_ms_ <= now.mono_ms) next_telemetry_ms_ = now.mono_ms + period_ms;
  }
  for (auto it = pending_param_sets_.begin(); it != pending_param_sets_.end();) {
    if (now.mono_ms - it->sent_ms < config_.param_set_timeout_ms) {
      ++it;
      continue;
    }
    const size_t index = it->index;
    it = pending_param_sets_.erase(it);
    ++counters_.param_sets_timed_out;
    refuse_param_set(index, "no answer from the controller");
  }
  if (upload_.active && now.mono_ms - upload_.last_request_ms >= config_.mission_item_timeout_ms) {
    if (upload_.retries < config_.mission_max_retries) {
      ++upload_.retries;
      ++counters_.mission_request_retries;
      // No item yet: maybe the GCS answers only the other request message. Ask both ways in turn.
      if (!upload_.answered) upload_.legacy = !upload_.legacy;
      request_next_item(now);
    } else {
      ++counters_.mission_uploads_timed_out;
      upload_.active = false;
      send_mission_ack(upload_.partner_sys, upload_.partner_comp, MAV_MISSION_OPERATION_CANCELLED,
                       MAV_MISSION_TYPE_MISSION);
      send_statustext(MAV_SEVERITY_WARNING, "Mission upload timed out, old mission kept");
    }
  }
}

namespace {
template <typename T>
std::vector<T> take(std::vector<T>* v) {
  std::vector<T> out;
  out.swap(*v);
  return out;
}
}  // namespace

std::vector<std::vector<uint8_t>> GsCore::take_frames() { return take(&frames_); }
std::vector<WayPlan> GsCore::take_way_plans() { return take(&way_plans_); }
std::vector<OperatorRequest> GsCore::take_operator_requests() { return take(&operator_requests_); }
std::vector<ParamSetRequest> GsCore::take_param_set_requests() { return take(&param_set_requests_); }

}  // namespace microhard_gs
