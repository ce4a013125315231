// The mission microservice (gs_mission_service.h).
#include <algorithm>
#include <cmath>
#include <cstring>

#include "gs_mission_service.h"

namespace microhard_gs {
namespace {

// How long after finishing an upload a repeated last item still gets its MISSION_ACK again.
constexpr uint64_t kReAckWindowMs = 10000;

// MISSION_REQUEST and MISSION_REQUEST_INT ask for item seq of the partner's mission alike.
template <typename Request>
Request item_request(uint8_t partner_sys, uint8_t partner_comp, uint16_t seq) {
  Request r{};
  r.target_system = partner_sys;
  r.target_component = partner_comp;
  r.seq = seq;
  r.mission_type = MAV_MISSION_TYPE_MISSION;
  return r;
}

}  // namespace

void MissionService::send_ack(uint8_t sys, uint8_t comp, uint8_t result, uint8_t mission_type) {
  mavlink_mission_ack_t a{};
  a.target_system = sys;
  a.target_component = comp;
  a.type = result;
  a.mission_type = mission_type;
  out_.emit([&](mavlink_message_t* m) {
    mavlink_msg_mission_ack_encode_status(out_.system_id(), out_.component_id(), out_.status(), m,
                                          &a);
  });
}

void MissionService::clear() {
  upload_.active = false;
  count_ = 0;
  plan_ = WayPlan{};
  way_plans_.push_back(WayPlan{});
}

void MissionService::on_count(const mavlink_message_t& msg, const mavlink_mission_count_t& m,
                              const Clock& now) {
  if (m.mission_type != MAV_MISSION_TYPE_MISSION) {
    // No geofence or rally points on this vehicle.
    send_ack(msg.sysid, msg.compid, MAV_MISSION_UNSUPPORTED, m.mission_type);
    return;
  }
  if (m.count > kMaxMissionItems) {
    ++counters_.missions_rejected;
    upload_.active = false;
    const std::string why = "Mission rejected: " + std::to_string(m.count) + " items, max " +
                            std::to_string(kMaxMissionItems);
    send_ack(msg.sysid, msg.compid, MAV_MISSION_NO_SPACE, MAV_MISSION_TYPE_MISSION);
    out_.statustext(MAV_SEVERITY_WARNING, why);
    return;
  }
  if (m.count == 0) {  // an empty upload clears the mission
    clear();
    ++counters_.missions_accepted;
    send_ack(msg.sysid, msg.compid, MAV_MISSION_ACCEPTED, MAV_MISSION_TYPE_MISSION);
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

void MissionService::request_next_item(const Clock& now) {
  const uint16_t seq = static_cast<uint16_t>(upload_.next_seq);
  if (upload_.legacy) {
    const auto r =
        item_request<mavlink_mission_request_t>(upload_.partner_sys, upload_.partner_comp, seq);
    out_.emit([&](mavlink_message_t* m) {
      mavlink_msg_mission_request_encode_status(out_.system_id(), out_.component_id(),
                                                out_.status(), m, &r);
    });
  } else {
    const auto r =
        item_request<mavlink_mission_request_int_t>(upload_.partner_sys, upload_.partner_comp, seq);
    out_.emit([&](mavlink_message_t* m) {
      mavlink_msg_mission_request_int_encode_status(out_.system_id(), out_.component_id(),
                                                    out_.status(), m, &r);
    });
  }
  upload_.last_request_ms = now.mono_ms;
}

void MissionService::finish_upload(uint8_t result, const std::string& reason, const Clock& now) {
  send_ack(upload_.partner_sys, upload_.partner_comp, result, MAV_MISSION_TYPE_MISSION);
  if (result != MAV_MISSION_ACCEPTED) {
    ++counters_.missions_rejected;
    out_.statustext(MAV_SEVERITY_WARNING, "Mission rejected: " + reason);
  }
  last_upload_.valid = true;
  last_upload_.partner_sys = upload_.partner_sys;
  last_upload_.partner_comp = upload_.partner_comp;
  last_upload_.last_seq = upload_.next_seq;
  last_upload_.result = result;
  last_upload_.finished_ms = now.mono_ms;
  upload_.active = false;
}

void MissionService::accept(const WayPlan& plan, const Clock& now) {
  std::copy(upload_.items, upload_.items + upload_.count, items_);
  count_ = upload_.count;
  plan_ = plan;
  way_plans_.push_back(plan);
  ++counters_.missions_accepted;
  finish_upload(MAV_MISSION_ACCEPTED, "", now);
  const bool home_row = is_home_row(items_[0], vehicle_.home, config_.limits);
  out_.statustext(MAV_SEVERITY_INFO, "Mission accepted: " + std::to_string(plan.fp) + " waypoints" +
                                         (home_row ? ", item 0 is home (not flown)" : ""));
}

void MissionService::on_item(const mavlink_message_t& msg, const MissionItem& item,
                             uint8_t mission_type, bool legacy, const Clock& now) {
  if (mission_type != MAV_MISSION_TYPE_MISSION) return;
  if (!upload_.active || msg.sysid != upload_.partner_sys || msg.compid != upload_.partner_comp) {
    // The GCS repeats the last item when our final MISSION_ACK was lost: answer it again.
    if (last_upload_.valid && msg.sysid == last_upload_.partner_sys &&
        msg.compid == last_upload_.partner_comp && item.seq == last_upload_.last_seq &&
        now.mono_ms - last_upload_.finished_ms < kReAckWindowMs) {
      send_ack(msg.sysid, msg.compid, last_upload_.result, MAV_MISSION_TYPE_MISSION);
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
  const MissionVerdict v = vehicle_.home_known
                               ? check_mission_item(item, vehicle_.home, config_.limits)
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
  const MissionVerdict all =
      build_way_plan(upload_.items, upload_.count, vehicle_.home, config_.limits, &plan);
  if (!all.ok()) {
    finish_upload(all.result, all.reason, now);
    return;
  }
  accept(plan, now);
}

void MissionService::on_request_list(const mavlink_message_t& msg, uint8_t mission_type) {
  mavlink_mission_count_t c{};
  c.target_system = msg.sysid;
  c.target_component = msg.compid;
  c.count = mission_type == MAV_MISSION_TYPE_MISSION ? static_cast<uint16_t>(count_) : 0;
  c.mission_type = mission_type;
  out_.emit([&](mavlink_message_t* m) {
    mavlink_msg_mission_count_encode_status(out_.system_id(), out_.component_id(), out_.status(), m,
                                            &c);
  });
}

void MissionService::on_request(const mavlink_message_t& msg, uint16_t seq, uint8_t mission_type,
                                bool legacy) {
  if (mission_type != MAV_MISSION_TYPE_MISSION || seq >= count_) {
    send_ack(msg.sysid, msg.compid, MAV_MISSION_INVALID_SEQUENCE, mission_type);
    return;
  }
  // Downloads answer in the frame each item was uploaded in (mission_frames.h).
  if (legacy) {
    mavlink_mission_item_t item = to_item_float(items_[seq]);
    item.target_system = msg.sysid;
    item.target_component = msg.compid;
    item.current = seq == 0 ? 1 : 0;
    out_.emit([&](mavlink_message_t* m) {
      mavlink_msg_mission_item_encode_status(out_.system_id(), out_.component_id(), out_.status(),
                                             m, &item);
    });
  } else {
    mavlink_mission_item_int_t item = to_item_int(items_[seq]);
    item.target_system = msg.sysid;
    item.target_component = msg.compid;
    item.current = seq == 0 ? 1 : 0;
    out_.emit([&](mavlink_message_t* m) {
      mavlink_msg_mission_item_int_encode_status(out_.system_id(), out_.component_id(),
                                                 out_.status(), m, &item);
    });
  }
}

void MissionService::on_clear_all(const mavlink_message_t& msg, uint8_t mission_type) {
  if (mission_type == MAV_MISSION_TYPE_MISSION || mission_type == MAV_MISSION_TYPE_ALL) clear();
  send_ack(msg.sysid, msg.compid, MAV_MISSION_ACCEPTED, mission_type);
}

void MissionService::on_ack(const mavlink_message_t& msg) {
  mavlink_mission_ack_t a;
  mavlink_msg_mission_ack_decode(&msg, &a);
  // The GCS gives up on an upload: drop it, the stored mission is untouched.
  if (upload_.active && msg.sysid == upload_.partner_sys && a.type != MAV_MISSION_ACCEPTED &&
      a.mission_type == MAV_MISSION_TYPE_MISSION) {
    upload_.active = false;
  }
}

void MissionService::tick(const Clock& now) {
  if (!upload_.active || now.mono_ms - upload_.last_request_ms < config_.item_timeout_ms) return;
  if (upload_.retries < config_.max_retries) {
    ++upload_.retries;
    ++counters_.mission_request_retries;
    // No item yet: maybe the GCS answers only the other request message. Ask both ways in turn.
    if (!upload_.answered) upload_.legacy = !upload_.legacy;
    request_next_item(now);
  } else {
    ++counters_.mission_uploads_timed_out;
    upload_.active = false;
    send_ack(upload_.partner_sys, upload_.partner_comp, MAV_MISSION_OPERATION_CANCELLED,
             MAV_MISSION_TYPE_MISSION);
    out_.statustext(MAV_SEVERITY_WARNING, "Mission upload timed out, old mission kept");
  }
}

std::vector<WayPlan> MissionService::take_way_plans() {
  std::vector<WayPlan> out;
  out.swap(way_plans_);
  return out;
}

}  // namespace microhard_gs
