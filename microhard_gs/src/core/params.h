// The controller's tunable parameters as the MAVLink parameter protocol sees them: a fixed-order
// table with 16-character ids.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace microhard_gs {

struct ParamSpec {
  const char* ros_name;  // key under the controller's parameter namespace
  const char* mav_id;    // MAVLink param_id: at most 16 characters
  bool is_integer;       // switches and selections are integers, gains and trims reals
};

// The controller's tunables, in the order of aircraft/<name>/tunables.yaml: the list the
// controller's ~set_tunable takes (both are generated from it, tunables_table.h). Not in it:
// hmcmd (a start-up command; commands travel as MAVLink commands and /operator_command, never as
// parameters), frame_id (a string), limits/ (the aircraft's envelope).
const std::vector<ParamSpec>& controller_param_specs();

class ParamTable {
 public:
  struct Entry {
    std::string mav_id;
    std::string ros_name;
    bool is_integer = false;
    double value = 0.0;  // the value in force in the controller, as far as we know
  };

  void add(const ParamSpec& spec, double value);
  size_t size() const { return entries_.size(); }
  const Entry& at(size_t index) const { return entries_[index]; }
  // Index of the parameter with this MAVLink id, or -1. `id` may lack a terminator when it is
  // exactly 16 characters, as on the wire.
  int find(const char* id, size_t id_len) const;
  // Index of the parameter with this ROS name, or -1.
  int find_ros_name(const std::string& ros_name) const;
  // Records the value the controller says is in force. Whether a value may be set at all, and
  // to what, is the controller's decision (its ~set_tunable), never this table's.
  void store(size_t index, double value);

 private:
  std::vector<Entry> entries_;
};

}  // namespace microhard_gs
