// Test and benchmark access to the aircraft's parameter files, flattened to the same keys the
// node sees in its private namespace ("dt", "limits/state/stall_speed_ftps").
#ifndef CONTROLLER_YAML_LOOKUP_H
#define CONTROLLER_YAML_LOOKUP_H

#include <yaml-cpp/yaml.h>

#include <map>
#include <string>

#include "controller_params.h"

namespace controller_test {

inline void flatten(const YAML::Node &node, const std::string &prefix,
                    std::map<std::string, double> *out) {
  for (const auto &kv : node) {
    const std::string key = prefix + kv.first.as<std::string>();
    if (kv.second.IsMap()) {
      flatten(kv.second, key + "/", out);
    } else if (kv.second.IsScalar()) {
      double v = 0.0;
      if (YAML::convert<double>::decode(kv.second, v)) {
        (*out)[key] = v;
      }
    }
  }
}

// The aircraft's parameters, with overrides applied on top (a test's deliberate change).
inline std::map<std::string, double> aircraft_params(
    const std::string &aircraft_dir, const std::map<std::string, double> &overrides = {}) {
  std::map<std::string, double> values;
  flatten(YAML::LoadFile(aircraft_dir + "/controller_param.yaml"), "", &values);
  flatten(YAML::LoadFile(aircraft_dir + "/limits.yaml"), "limits/", &values);
  for (const auto &kv : overrides) {
    values[kv.first] = kv.second;
  }
  return values;
}

inline controller::ParamLookup lookup_in(const std::map<std::string, double> &values) {
  return [&values](const std::string &key, double *v) {
    const auto it = values.find(key);
    if (it == values.end()) {
      return false;
    }
    *v = it->second;
    return true;
  };
}

}  // namespace controller_test

#endif
