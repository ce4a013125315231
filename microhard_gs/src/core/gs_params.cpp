// The parameter microservice: the tunables table, reads, and PARAM_SETs the controller answers.
#include "gs_core.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "gs_core_emit.h"

namespace microhard_gs {
namespace {

// A GCS (or a flood) can ask faster than the controller answers; more than this many waiting
// are refused at once rather than queued without bound.
constexpr size_t kMaxPendingParamSets = 16;

}  // namespace

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
    mavlink_msg_param_value_encode_status(config_.system_id, config_.component_id, &tx_status_, m,
                                          &pv);
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
  if (index >= 0 && static_cast<size_t>(index) < params_.size())
    send_param(static_cast<size_t>(index));
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
  send_statustext(MAV_SEVERITY_WARNING,
                  "Param " + params_.at(index).mav_id + " refused: " + reason);
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
    send_statustext(MAV_SEVERITY_NOTICE,
                    "Param " + params_.at(i).mav_id + " set after all (late answer)");
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

}  // namespace microhard_gs
