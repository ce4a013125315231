// The mission microservice: uploads checked whole against the limits (a bad one is rejected with
// the reason and the mission held stays), downloads, clear, acks. A mission accepted becomes a
// /way plan about the HA's home, which the node publishes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "gs_emitter.h"
#include "gs_types.h"
#include "mission.h"
#include "mission_frames.h"

namespace microhard_gs {

struct MissionConfig {
  MissionLimits limits;
  uint32_t item_timeout_ms = 1500;
  uint32_t max_retries = 5;
};

class MissionService {
 public:
  MissionService(const MissionConfig& config, const VehicleState& vehicle, Emitter& out,
                 Counters& counters)
      : config_(config), vehicle_(vehicle), out_(out), counters_(counters) {}
  MissionService(const MissionService&) = delete;
  MissionService& operator=(const MissionService&) = delete;

  // Messages already checked to be addressed to this vehicle; msg gives the sender.
  void on_count(const mavlink_message_t& msg, const mavlink_mission_count_t& m, const Clock& now);
  void on_item(const mavlink_message_t& msg, const MissionItem& item, uint8_t mission_type,
               bool legacy, const Clock& now);
  void on_request_list(const mavlink_message_t& msg, uint8_t mission_type);
  void on_request(const mavlink_message_t& msg, uint16_t seq, uint8_t mission_type, bool legacy);
  void on_clear_all(const mavlink_message_t& msg, uint8_t mission_type);
  void on_ack(const mavlink_message_t& msg);
  // Asks again for an item the GCS has not sent, and gives the upload up after max_retries.
  void tick(const Clock& now);

  std::vector<WayPlan> take_way_plans();
  int count() const { return count_; }
  bool upload_in_progress() const { return upload_.active; }
  const WayPlan& plan() const { return plan_; }

 private:
  struct Upload {
    bool active = false;
    // Ask with MISSION_REQUEST rather than MISSION_REQUEST_INT: the GCS answered with MISSION_ITEM,
    // or it answered only once asked that way (MAVProxy answers MISSION_REQUEST alone).
    bool legacy = false;
    bool answered = false;  // an item of this upload arrived: the way of asking is settled
    uint8_t partner_sys = 0, partner_comp = 0;
    int count = 0;
    int next_seq = 0;
    uint32_t retries = 0;
    uint64_t last_request_ms = 0;
    MissionItem items[kMaxMissionItems];
  };
  // The answer to the last finished upload, resent if the GCS repeats the last item because it
  // lost our MISSION_ACK.
  struct LastUploadResult {
    bool valid = false;
    uint8_t partner_sys = 0, partner_comp = 0;
    int last_seq = -1;
    uint8_t result = 0;
    uint64_t finished_ms = 0;
  };

  void request_next_item(const Clock& now);
  void finish_upload(uint8_t result, const std::string& reason, const Clock& now);
  void accept(const WayPlan& plan, const Clock& now);
  void clear();
  void send_ack(uint8_t sys, uint8_t comp, uint8_t result, uint8_t mission_type);

  MissionConfig config_;
  const VehicleState& vehicle_;
  Emitter& out_;
  Counters& counters_;
  Upload upload_;
  LastUploadResult last_upload_;
  MissionItem items_[kMaxMissionItems];
  int count_ = 0;
  WayPlan plan_;  // the plan of the mission held (its waypoints' item numbers)
  std::vector<WayPlan> way_plans_;
};

}  // namespace microhard_gs
