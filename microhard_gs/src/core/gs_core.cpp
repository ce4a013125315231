#include "gs_core.h"

#include <algorithm>
#include <utility>

namespace microhard_gs {

GsCore::GsCore(const GsConfig& config, const ParamTable& params)
    : config_(config),
      out_(config.system_id, config.component_id),
      params_(params, config.param_set_timeout_ms, out_, counters_),
      missions_(config.mission, vehicle_, out_, counters_),
      telemetry_(TelemetryConfig{config.telemetry_rate_hz, config.airborne_agl_ft}, vehicle_,
                 intent_, missions_, out_, counters_),
      commands_(config.airborne_agl_ft, vehicle_, intent_, telemetry_, out_, counters_) {
  if (config_.signing) start_signing();
}

void GsCore::handle_bytes(const uint8_t* data, size_t len, const Clock& now) {
  update_signing_clock(now);
  for (size_t i = 0; i < len; ++i) {
    mavlink_message_t msg;
    mavlink_status_t status;
    const uint8_t r = mavlink_frame_char_buffer(&rx_buffer_, &rx_status_, data[i], &msg, &status);
    rx_recent_[rx_recent_next_] = data[i];
    rx_recent_next_ = (rx_recent_next_ + 1) % MAVLINK_MAX_PACKET_LEN;
    if (config_.keep_received_frames &&
        (r == MAVLINK_FRAMING_OK || r == MAVLINK_FRAMING_BAD_SIGNATURE)) {
      keep_received_frame(msg);
    }
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
      deny_command(msg);
    }
  }
}

// An unsigned command still gets an answer, so the operator learns why nothing happened.
void GsCore::deny_command(const mavlink_message_t& msg) {
  if (msg.msgid == MAVLINK_MSG_ID_COMMAND_LONG) {
    mavlink_command_long_t c;
    mavlink_msg_command_long_decode(&msg, &c);
    if (c.target_system == config_.system_id) commands_.deny(msg, c.command);
  } else if (msg.msgid == MAVLINK_MSG_ID_COMMAND_INT) {
    mavlink_command_int_t c;
    mavlink_msg_command_int_decode(&msg, &c);
    if (c.target_system == config_.system_id) commands_.deny(msg, c.command);
  }
}

void GsCore::set_telemetry(const Telemetry& t, const Clock& now) {
  vehicle_.telemetry = t;
  vehicle_.have_telemetry = true;
  vehicle_.telemetry_ms = now.mono_ms;
}

void GsCore::keep_received_frame(const mavlink_message_t& msg) {
  // msg.len is the payload length as received (a MAVLink 2 sender trims trailing zeros; the
  // parser only pads its copy), so this is the frame's length on the wire.
  const bool v1 = msg.magic == MAVLINK_STX_MAVLINK1;
  const bool is_signed = !v1 && (msg.incompat_flags & MAVLINK_IFLAG_SIGNED) != 0;
  const size_t len = (v1 ? MAVLINK_CORE_HEADER_MAVLINK1_LEN : MAVLINK_CORE_HEADER_LEN) + 1u +
                     msg.len + MAVLINK_NUM_CHECKSUM_BYTES +
                     (is_signed ? MAVLINK_SIGNATURE_BLOCK_LEN : 0u);
  std::vector<uint8_t> frame(len);
  size_t at = (rx_recent_next_ + MAVLINK_MAX_PACKET_LEN - len) % MAVLINK_MAX_PACKET_LEN;
  for (size_t k = 0; k < len; ++k, at = (at + 1) % MAVLINK_MAX_PACKET_LEN)
    frame[k] = rx_recent_[at];
  received_frames_.push_back(std::move(frame));
}

bool GsCore::addressed_to_us(uint8_t target_system, uint8_t target_component) {
  const bool ok = (target_system == 0 || target_system == config_.system_id) &&
                  (target_component == 0 || target_component == config_.component_id);
  if (!ok) ++counters_.ignored_other_target;
  return ok;
}

template <typename Msg, typename Handle>
bool GsCore::if_addressed(const mavlink_message_t& msg,
                          void (*decode)(const mavlink_message_t*, Msg*), Handle handle) {
  Msg m;
  decode(&msg, &m);
  if (addressed_to_us(m.target_system, m.target_component)) handle(m);
  return true;
}

// The parameter service's messages; false for any other.
bool GsCore::route_params(const mavlink_message_t& msg, const Clock& now) {
  switch (msg.msgid) {
    case MAVLINK_MSG_ID_PARAM_REQUEST_LIST:
      return if_addressed(msg, mavlink_msg_param_request_list_decode,
                          [&](const auto&) { params_.on_request_list(); });
    case MAVLINK_MSG_ID_PARAM_REQUEST_READ:
      return if_addressed(msg, mavlink_msg_param_request_read_decode,
                          [&](const auto& m) { params_.on_request_read(m); });
    case MAVLINK_MSG_ID_PARAM_SET:
      return if_addressed(msg, mavlink_msg_param_set_decode,
                          [&](const auto& m) { params_.on_set(m, now); });
    default:
      return false;
  }
}

// The mission service's messages; false for any other.
bool GsCore::route_mission(const mavlink_message_t& msg, const Clock& now) {
  switch (msg.msgid) {
    case MAVLINK_MSG_ID_MISSION_COUNT:
      return if_addressed(msg, mavlink_msg_mission_count_decode,
                          [&](const auto& m) { missions_.on_count(msg, m, now); });
    case MAVLINK_MSG_ID_MISSION_ITEM_INT:
      return if_addressed(msg, mavlink_msg_mission_item_int_decode, [&](const auto& m) {
        missions_.on_item(msg, from_item_int(m), m.mission_type, false, now);
      });
    case MAVLINK_MSG_ID_MISSION_ITEM:
      return if_addressed(msg, mavlink_msg_mission_item_decode, [&](const auto& m) {
        missions_.on_item(msg, from_item_float(m), m.mission_type, true, now);
      });
    case MAVLINK_MSG_ID_MISSION_REQUEST_LIST:
      return if_addressed(msg, mavlink_msg_mission_request_list_decode,
                          [&](const auto& m) { missions_.on_request_list(msg, m.mission_type); });
    case MAVLINK_MSG_ID_MISSION_REQUEST_INT:
      return if_addressed(msg, mavlink_msg_mission_request_int_decode, [&](const auto& r) {
        missions_.on_request(msg, r.seq, r.mission_type, false);
      });
    case MAVLINK_MSG_ID_MISSION_REQUEST:
      return if_addressed(msg, mavlink_msg_mission_request_decode, [&](const auto& r) {
        missions_.on_request(msg, r.seq, r.mission_type, true);
      });
    case MAVLINK_MSG_ID_MISSION_CLEAR_ALL:
      return if_addressed(msg, mavlink_msg_mission_clear_all_decode,
                          [&](const auto& m) { missions_.on_clear_all(msg, m.mission_type); });
    case MAVLINK_MSG_ID_MISSION_ACK:
      missions_.on_ack(msg);
      return true;
    default:
      return false;
  }
}

// The command service's messages; false for any other.
bool GsCore::route_command(const mavlink_message_t& msg) {
  CommandArgs a;
  uint8_t target_system = 0, target_component = 0;
  if (msg.msgid == MAVLINK_MSG_ID_COMMAND_LONG) {
    mavlink_command_long_t c;
    mavlink_msg_command_long_decode(&msg, &c);
    a.command = c.command;
    const float p[7] = {c.param1, c.param2, c.param3, c.param4, c.param5, c.param6, c.param7};
    std::copy(p, p + 7, a.params);
    target_system = c.target_system;
    target_component = c.target_component;
  } else if (msg.msgid == MAVLINK_MSG_ID_COMMAND_INT) {
    mavlink_command_int_t c;
    mavlink_msg_command_int_decode(&msg, &c);
    a.command = c.command;
    const float p[7] = {
        c.param1, c.param2, c.param3, c.param4, static_cast<float>(c.x), static_cast<float>(c.y),
        c.z};
    std::copy(p, p + 7, a.params);
    a.is_int = true;
    a.x_e7 = c.x;
    a.y_e7 = c.y;
    target_system = c.target_system;
    target_component = c.target_component;
  } else {
    return false;
  }
  if (addressed_to_us(target_system, target_component)) commands_.on_command(msg, a);
  return true;
}

// Anything else is not for us (GCS heartbeats, radio status, ...).
void GsCore::dispatch(const mavlink_message_t& msg, const Clock& now) {
  if (route_params(msg, now) || route_mission(msg, now)) return;
  (void)route_command(msg);
}

void GsCore::tick(const Clock& now) {
  update_signing_clock(now);
  telemetry_.tick(now);
  params_.tick(now);
  missions_.tick(now);
}

namespace {
template <typename T>
std::vector<T> take(std::vector<T>* v) {
  std::vector<T> out;
  out.swap(*v);
  return out;
}
}  // namespace

std::vector<std::vector<uint8_t>> GsCore::take_frames() { return out_.take_frames(); }
std::vector<std::vector<uint8_t>> GsCore::take_received_frames() { return take(&received_frames_); }
std::vector<WayPlan> GsCore::take_way_plans() { return missions_.take_way_plans(); }
std::vector<ParamSetRequest> GsCore::take_param_set_requests() { return params_.take_requests(); }

}  // namespace microhard_gs
