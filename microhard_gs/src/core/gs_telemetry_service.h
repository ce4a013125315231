// The telemetry a ground station draws the aircraft with: HEARTBEAT and CURRENT_MODE every
// second; at the configured rate SYS_STATUS, and with fresh telemetry ATTITUDE,
// GLOBAL_POSITION_INT, VFR_HUD, GPS_RAW_INT, HOME_POSITION and MISSION_CURRENT; and the messages
// a GCS asks for by command (AUTOPILOT_VERSION, HOME_POSITION, CURRENT_MODE, AVAILABLE_MODES).
#pragma once

#include <cstdint>

#include "gs_emitter.h"
#include "gs_mission_service.h"
#include "gs_types.h"

namespace microhard_gs {

struct TelemetryConfig {
  double rate_hz = 0.0;          // the periodic set (0: none)
  double airborne_agl_ft = 0.0;  // above this the HEARTBEAT says armed and active
};

class TelemetryService {
 public:
  TelemetryService(const TelemetryConfig& config, const VehicleState& vehicle,
                   const OperatorIntent& intent, const MissionService& missions, Emitter& out,
                   Counters& counters)
      : config_(config),
        vehicle_(vehicle),
        intent_(intent),
        missions_(missions),
        out_(out),
        counters_(counters) {}
  TelemetryService(const TelemetryService&) = delete;
  TelemetryService& operator=(const TelemetryService&) = delete;

  // The schedule: the first call starts the vehicle's boot clock and sends at once.
  void tick(const Clock& now);

  void send_home_position();  // nothing before home is known
  void send_current_mode();
  void send_available_mode(int mode_index);  // 1..kModeCount; nothing outside
  void send_autopilot_version();

 private:
  void send_heartbeat();
  void send_set(const Clock& now);
  void send_sys_status(bool fresh);
  void send_attitude(uint32_t boot_ms);
  void send_position(uint32_t boot_ms);
  void send_mission_current();

  TelemetryConfig config_;
  const VehicleState& vehicle_;
  const OperatorIntent& intent_;
  const MissionService& missions_;
  Emitter& out_;
  Counters& counters_;
  bool started_ = false;
  uint64_t boot_ms_ = 0;
  uint64_t next_heartbeat_ms_ = 0;
  uint64_t next_set_ms_ = 0;
};

}  // namespace microhard_gs
