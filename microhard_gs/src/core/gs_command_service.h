// The command microservice: COMMAND_LONG and COMMAND_INT become operator requests for the HA
// (select HP or HA, restart the HP, self-test, set home) or the messages a GCS asks for, each
// answered with its COMMAND_ACK. ACCEPTED for an operator request means "forwarded to the HA":
// the HA's checks still decide.
#pragma once

#include <cstdint>
#include <vector>

#include "geo.h"
#include "gs_emitter.h"
#include "gs_telemetry_service.h"
#include "gs_types.h"

namespace microhard_gs {

// Operator requests; values match drone_ros/OperatorCommand's constants.
enum class OperatorRequest : uint8_t {
  kSelectHp = 1,
  kSelectHa = 2,
  kRestartHp = 3,
  kSelfTest = 4
};

// A SET_HOME for the HA to decide (OperatorCommand SET_HOME): to a position, or where the HA's
// INS says the aircraft is (use_current).
struct HomeRequest {
  bool use_current = false;
  GeoPoint position;
};

// A command as either message carries it. COMMAND_INT's x and y as sent (deg x 1e7): through a
// float param a new home would land a metre off.
struct CommandArgs {
  uint16_t command = 0;
  float params[7] = {};
  bool is_int = false;
  int32_t x_e7 = 0, y_e7 = 0;
};

class CommandService {
 public:
  // airborne_agl_ft: above it the self-test and SET_HOME are refused.
  CommandService(double airborne_agl_ft, const VehicleState& vehicle, OperatorIntent& intent,
                 TelemetryService& telemetry, Emitter& out, Counters& counters)
      : airborne_agl_ft_(airborne_agl_ft),
        vehicle_(vehicle),
        intent_(intent),
        telemetry_(telemetry),
        out_(out),
        counters_(counters) {}
  CommandService(const CommandService&) = delete;
  CommandService& operator=(const CommandService&) = delete;

  // A command already checked to be addressed to this vehicle; msg gives the sender.
  void on_command(const mavlink_message_t& msg, const CommandArgs& c);
  // A command refused before it is read (unsigned while signing is on): DENIED, so the
  // operator learns why nothing happened.
  void deny(const mavlink_message_t& msg, uint16_t command);

  std::vector<OperatorRequest> take_operator_requests();
  std::vector<HomeRequest> take_home_requests();

 private:
  void ack(const mavlink_message_t& msg, uint16_t command, uint8_t result);
  uint8_t execute(const CommandArgs& c);
  // MAV_CMD_DO_SET_HOME; lat/lon in degrees.
  uint8_t set_home(float use_current, double lat_deg, double lon_deg, float alt_m);
  // The messages an accepted request asks for, after its ACK.
  void send_requested(const CommandArgs& c);

  double airborne_agl_ft_;
  const VehicleState& vehicle_;
  OperatorIntent& intent_;
  TelemetryService& telemetry_;
  Emitter& out_;
  Counters& counters_;
  std::vector<OperatorRequest> operator_requests_;
  std::vector<HomeRequest> home_requests_;
};

}  // namespace microhard_gs
