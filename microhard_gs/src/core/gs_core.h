// The ground-station bridge without ROS and without sockets: bytes and time in, MAVLink frames
// and requests for the ROS side out. Everything here is driven by the caller's clock, so the
// mission state machine's timeouts and the telemetry schedule run on a simulated clock in tests.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "geo.h"
#include "gs_command_service.h"
#include "gs_emitter.h"
#include "gs_mission_service.h"
#include "gs_param_service.h"
#include "gs_telemetry_service.h"
#include "gs_types.h"
#include "mavlink_all.h"
#include "mission.h"
#include "mission_frames.h"
#include "modes.h"
#include "params.h"
#include "signing_key.h"

namespace microhard_gs {

struct GsConfig {
  uint8_t system_id = 1;
  uint8_t component_id = MAV_COMP_ID_AUTOPILOT1;
  double telemetry_rate_hz = 0.0;
  double airborne_agl_ft = 0.0;  // above this the vehicle reports itself armed/flying
  MissionConfig mission;         // the limits a mission is checked against, the upload's timeout
  // How long a PARAM_SET waits for the controller's answer before the GCS is told it failed;
  // under QGroundControl's own wait for the echo, so it does not resend meanwhile.
  uint32_t param_set_timeout_ms = 500;
  bool signing = false;
  SigningKey signing_key{};
  uint8_t signing_link_id = 0;
  // Keep every frame received, as it came, for take_received_frames() (the telemetry log).
  bool keep_received_frames = false;
};

class GsCore {
 public:
  // The config is assumed validated by the caller (the node's parameter reader).
  GsCore(const GsConfig& config, const ParamTable& params);
  GsCore(const GsCore&) = delete;
  GsCore& operator=(const GsCore&) = delete;

  // Bytes from the link, in any chunking. Corrupt frames are counted and dropped.
  void handle_bytes(const uint8_t* data, size_t len, const Clock& now);
  // Runs the telemetry schedule and the mission upload timeouts. Call at least every 10 ms.
  void tick(const Clock& now);

  void set_telemetry(const Telemetry& t, const Clock& now);
  // Home from its one owner, the HA (/home): the origin of /way and HOME_POSITION (gs_home.cpp).
  // Returns false, keeping the old home, for a position that is not valid.
  bool set_home(const GeoPoint& home);
  // Announces every change of the controller in charge, and the first status seen, as a
  // STATUSTEXT naming the reason.
  void set_decision(const DecisionInfo& d);

  // Outputs, drained by the caller.
  std::vector<std::vector<uint8_t>> take_frames();
  // With keep_received_frames: every frame received whole with a good CRC, byte for byte as it
  // came, whether acted on or refused (signing, another target): what the link carried.
  std::vector<std::vector<uint8_t>> take_received_frames();
  std::vector<WayPlan> take_way_plans();
  std::vector<OperatorRequest> take_operator_requests() {
    return commands_.take_operator_requests();
  }
  std::vector<HomeRequest> take_home_requests() { return commands_.take_home_requests(); }
  std::vector<ParamSetRequest> take_param_set_requests();
  // The controller's answer to a request: PARAM_VALUE with the value now in force, plus a
  // STATUSTEXT naming the reason when refused. An answer after the timeout (the GCS has already
  // been told the set failed) that accepted the change still updates the table and announces
  // the new value, since that is what the controller flies with.
  void param_set_answered(const ParamSetRequest& request, const ParamSetAnswer& answer) {
    params_.answered(request, answer);
  }

  const Counters& counters() const { return counters_; }
  bool home_known() const { return vehicle_.home_known; }
  const GeoPoint& home() const { return vehicle_.home; }
  int mission_count() const { return missions_.count(); }
  bool upload_in_progress() const { return missions_.upload_in_progress(); }
  const ParamTable& params() const { return params_.table(); }
  // The last decision status (nullptr before the first): who flies and the height the HEARTBEAT's
  // armed bit, SET_HOME and the self-test go by.
  const DecisionInfo* decision() const {
    return vehicle_.have_decision ? &vehicle_.decision : nullptr;
  }

 private:
  // GsCore routes what arrives to its service, runs their schedules, signs the link
  // (gs_signing.cpp) and alone writes the vehicle state (set_telemetry, set_home in gs_home.cpp,
  // set_decision in gs_statustext.cpp). Each MAVLink microservice is a service of its own over
  // the one Emitter, reading vehicle_: ParamService, MissionService, TelemetryService,
  // CommandService.
  void start_signing();
  void update_signing_clock(const Clock& now);
  void dispatch(const mavlink_message_t& msg, const Clock& now);
  bool route_params(const mavlink_message_t& msg, const Clock& now);
  bool route_mission(const mavlink_message_t& msg, const Clock& now);
  bool route_command(const mavlink_message_t& msg);
  // The DENIED a command gets when its frame is refused for its signature.
  void deny_command(const mavlink_message_t& msg);
  void keep_received_frame(const mavlink_message_t& msg);
  bool addressed_to_us(uint8_t target_system, uint8_t target_component);
  // Decodes msg as a Msg and calls handle(m) if it is addressed to this vehicle; true (the
  // message was the caller's to route, addressed here or not).
  template <typename Msg, typename Handle>
  bool if_addressed(const mavlink_message_t& msg, void (*decode)(const mavlink_message_t*, Msg*),
                    Handle handle);

  GsConfig config_;
  Counters counters_;
  // The services' shared way out, then the services (in this order: they hold references to it).
  Emitter out_;
  ParamService params_;
  VehicleState vehicle_;
  OperatorIntent intent_;
  MissionService missions_;
  TelemetryService telemetry_;
  CommandService commands_;

  mavlink_status_t rx_status_{};
  mavlink_message_t rx_buffer_{};
  // The last bytes received, a ring as long as the longest frame: a frame just parsed is its
  // last bytes, whatever the chunking and whatever came before it.
  uint8_t rx_recent_[MAVLINK_MAX_PACKET_LEN] = {};
  size_t rx_recent_next_ = 0;
  std::vector<std::vector<uint8_t>> received_frames_;
  mavlink_signing_t signing_{};
  mavlink_signing_streams_t signing_streams_{};
};

// Names of the DecisionStatus REASON_* bits set in `reasons`, comma separated ("NO_COMMAND,STALL").
std::string reason_names(uint32_t reasons);
// The STATUSTEXT for a decision status that changes who flies, naming why ("Controller HP->HA:
// NO_COMMAND,STALL"); `previous` is null for the first status seen. Sets *severity.
std::string decision_announcement(const DecisionInfo* previous, const DecisionInfo& now,
                                  uint8_t* severity);

}  // namespace microhard_gs
