#include "params.h"

#include <cmath>
#include <cstring>

#include "tunables_table.h"

namespace microhard_gs {

const std::vector<ParamSpec>& controller_param_specs() {
  static const std::vector<ParamSpec> specs = [] {
    std::vector<ParamSpec> out;
    for (const tunables::Tunable& t : tunables::kTunables)
      out.push_back(ParamSpec{t.name, t.mav_id, t.is_integer});
    return out;
  }();
  return specs;
}

void ParamTable::add(const ParamSpec& spec, double value) {
  Entry e;
  e.mav_id = spec.mav_id;
  e.ros_name = spec.ros_name;
  e.is_integer = spec.is_integer;
  e.value = spec.is_integer ? std::round(value) : value;
  entries_.push_back(e);
}

int ParamTable::find(const char* id, size_t id_len) const {
  const size_t len = strnlen(id, id_len);
  for (size_t i = 0; i < entries_.size(); ++i) {
    if (entries_[i].mav_id.size() == len && std::memcmp(entries_[i].mav_id.data(), id, len) == 0) {
      return static_cast<int>(i);
    }
  }
  return -1;
}

int ParamTable::find_ros_name(const std::string& ros_name) const {
  for (size_t i = 0; i < entries_.size(); ++i) {
    if (entries_[i].ros_name == ros_name) return static_cast<int>(i);
  }
  return -1;
}

void ParamTable::store(size_t index, double value) {
  if (index >= entries_.size() || !std::isfinite(value)) return;
  Entry& e = entries_[index];
  e.value = e.is_integer ? std::round(value) : value;
}

}  // namespace microhard_gs
