// The parameter microservice (gs_param_service.h).
#include "gs_param_service.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace microhard_gs {
namespace {

// A GCS (or a flood) can ask faster than the controller answers; more than this many waiting
// are refused at once rather than queued without bound.
constexpr size_t kMaxPendingParamSets = 16;

}  // namespace

void ParamService::send(size_t index) {
  const ParamTable::Entry& e = table_.at(index);
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
  pv.param_count = static_cast<uint16_t>(table_.size());
  pv.param_index = static_cast<uint16_t>(index);
  out_.emit([&](mavlink_message_t* m) {
    mavlink_msg_param_value_encode_status(out_.system_id(), out_.component_id(), out_.status(), m,
                                          &pv);
  });
}

void ParamService::on_request_list() {
  for (size_t i = 0; i < table_.size(); ++i) send(i);
}

void ParamService::on_request_read(const mavlink_param_request_read_t& m) {
  int index = m.param_index;
  if (index < 0) {
    char id[sizeof m.param_id];
    std::memcpy(id, m.param_id, sizeof id);
    index = table_.find(id, sizeof id);
  }
  if (index >= 0 && static_cast<size_t>(index) < table_.size()) send(static_cast<size_t>(index));
}

void ParamService::on_set(const mavlink_param_set_t& m, const Clock& now) {
  char id[sizeof m.param_id];
  std::memcpy(id, m.param_id, sizeof id);
  const int index = table_.find(id, sizeof id);
  if (index < 0) return;  // the protocol has no negative answer: the GCS times out
  const size_t i = static_cast<size_t>(index);
  double value = m.param_value;
  if (table_.at(i).is_integer && m.param_type != MAV_PARAM_TYPE_REAL32) {
    // Byte-wise encoding: the int32's bytes travel in the float. A REAL32-typed set of an
    // integer goes as it is; the controller refuses it unless whole.
    int32_t v;
    const float f = m.param_value;
    std::memcpy(&v, &f, sizeof v);
    value = v;
  }
  if (pending_.size() >= kMaxPendingParamSets) {
    refuse(i, "busy, too many sets waiting for the controller");
    return;
  }
  // No echo yet: the echo is the value in force, and only the controller knows it. Its range
  // checks are the ones its parameter files meet (one limit, one place).
  ParamSetRequest r;
  r.id = ++next_id_;
  r.ros_name = table_.at(i).ros_name;
  r.value = value;
  requests_.push_back(r);
  pending_.push_back(Pending{r.id, i, now.mono_ms});
}

void ParamService::tick(const Clock& now) {
  for (auto it = pending_.begin(); it != pending_.end();) {
    if (now.mono_ms - it->sent_ms < timeout_ms_) {
      ++it;
      continue;
    }
    const size_t index = it->index;
    it = pending_.erase(it);
    ++counters_.param_sets_timed_out;
    refuse(index, "no answer from the controller");
  }
}

std::vector<ParamSetRequest> ParamService::take_requests() {
  std::vector<ParamSetRequest> out;
  out.swap(requests_);
  return out;
}

void ParamService::refuse(size_t index, const std::string& reason) {
  ++counters_.param_sets_refused;
  send(index);  // the old value: how MAVLink tells a GCS that the set did not happen
  out_.statustext(MAV_SEVERITY_WARNING, "Param " + table_.at(index).mav_id + " refused: " + reason);
}

void ParamService::answered(const ParamSetRequest& request, const ParamSetAnswer& answer) {
  const auto it = std::find_if(pending_.begin(), pending_.end(),
                               [&](const Pending& p) { return p.id == request.id; });
  if (it == pending_.end()) {
    // Too late: the GCS was told the set failed. Only a change that did happen needs telling.
    const int index = table_.find_ros_name(request.ros_name);
    if (!answer.accepted || index < 0) return;
    const size_t i = static_cast<size_t>(index);
    table_.store(i, answer.value_in_force);
    ++counters_.param_sets_accepted;
    send(i);
    out_.statustext(MAV_SEVERITY_NOTICE,
                    "Param " + table_.at(i).mav_id + " set after all (late answer)");
    return;
  }
  const size_t i = it->index;
  pending_.erase(it);
  if (!answer.accepted) {
    refuse(i, answer.reason.empty() ? std::string("no reason given") : answer.reason);
    return;
  }
  table_.store(i, answer.value_in_force);
  ++counters_.param_sets_accepted;
  send(i);
}

}  // namespace microhard_gs
