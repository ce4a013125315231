// The parameter microservice: the controller's tunables as MAVLink parameters. Reads are
// answered from the table; a PARAM_SET becomes a request the controller decides (the node calls
// its ~set_tunable), and the GCS gets the value then in force, or the old one with the reason.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "gs_emitter.h"
#include "gs_types.h"
#include "params.h"

namespace microhard_gs {

class ParamService {
 public:
  // timeout_ms: how long a set waits for the controller before the GCS is told it failed.
  ParamService(const ParamTable& table, uint32_t timeout_ms, Emitter& out, Counters& counters)
      : table_(table), timeout_ms_(timeout_ms), out_(out), counters_(counters) {}

  // Messages already checked to be addressed to this vehicle.
  void on_request_list();
  void on_request_read(const mavlink_param_request_read_t& m);
  void on_set(const mavlink_param_set_t& m, const Clock& now);
  // Sets the controller has not answered in time are refused.
  void tick(const Clock& now);

  std::vector<ParamSetRequest> take_requests();
  void answered(const ParamSetRequest& request, const ParamSetAnswer& answer);
  const ParamTable& table() const { return table_; }

 private:
  struct Pending {
    uint32_t id = 0;
    size_t index = 0;
    uint64_t sent_ms = 0;
  };
  void send(size_t index);
  void refuse(size_t index, const std::string& reason);

  ParamTable table_;
  uint32_t timeout_ms_;
  Emitter& out_;
  Counters& counters_;
  std::vector<Pending> pending_;
  uint32_t next_id_ = 0;
  std::vector<ParamSetRequest> requests_;
};

}  // namespace microhard_gs
