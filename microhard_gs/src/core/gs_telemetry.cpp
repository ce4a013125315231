// The telemetry service (gs_telemetry_service.h).
#include <algorithm>
#include <cmath>
#include <cstring>

#include "geo.h"
#include "gs_telemetry_service.h"
#include "modes.h"

namespace microhard_gs {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr uint64_t kTelemetryStaleMs = 2000;  // stop claiming a position after this silence
constexpr uint64_t kHeartbeatPeriodMs = 1000;

int32_t clamp_i32(double v) {
  if (!std::isfinite(v)) return 0;
  return static_cast<int32_t>(std::max(-2147483647.0, std::min(2147483647.0, std::round(v))));
}
int16_t clamp_i16(double v) {
  if (!std::isfinite(v)) return 0;
  return static_cast<int16_t>(std::max(-32767.0, std::min(32767.0, std::round(v))));
}
uint16_t clamp_u16(double v) {
  if (!std::isfinite(v) || v < 0.0) return 0;
  return static_cast<uint16_t>(std::min(65534.0, std::round(v)));
}
float finite_or_zero(double v) { return std::isfinite(v) ? static_cast<float>(v) : 0.0f; }

double heading_deg(double yaw_rad) {
  double h = std::fmod(yaw_rad * 180.0 / kPi, 360.0);
  if (h < 0.0) h += 360.0;
  return std::isfinite(h) ? h : 0.0;
}

}  // namespace

void TelemetryService::send_autopilot_version() {
  mavlink_autopilot_version_t v{};
  v.capabilities = MAV_PROTOCOL_CAPABILITY_MISSION_INT | MAV_PROTOCOL_CAPABILITY_MAVLINK2 |
                   MAV_PROTOCOL_CAPABILITY_COMMAND_INT |
                   MAV_PROTOCOL_CAPABILITY_PARAM_ENCODE_BYTEWISE;
  v.flight_sw_version = 0x00010000u;  // 0.1.0, the drone_ros package version
  v.uid = out_.system_id();
  out_.emit([&](mavlink_message_t* m) {
    mavlink_msg_autopilot_version_encode_status(out_.system_id(), out_.component_id(),
                                                out_.status(), m, &v);
  });
}

void TelemetryService::send_home_position() {
  if (!vehicle_.home_known) return;
  mavlink_home_position_t h{};
  h.latitude = clamp_i32(vehicle_.home.lat_deg * 1e7);
  h.longitude = clamp_i32(vehicle_.home.lon_deg * 1e7);
  h.altitude = clamp_i32(vehicle_.home.alt_m * 1000.0);
  h.q[0] = 1.0f;
  out_.emit([&](mavlink_message_t* m) {
    mavlink_msg_home_position_encode_status(out_.system_id(), out_.component_id(), out_.status(), m,
                                            &h);
  });
}

void TelemetryService::send_available_mode(int mode_index) {
  mavlink_available_modes_t m{};
  if (!available_mode(mode_index, &m)) return;
  out_.emit([&](mavlink_message_t* out) {
    mavlink_msg_available_modes_encode_status(out_.system_id(), out_.component_id(), out_.status(),
                                              out, &m);
  });
}

void TelemetryService::send_current_mode() {
  const mavlink_current_mode_t m =
      current_mode(vehicle_.have_decision, vehicle_.decision.controller, intent_.custom_mode);
  out_.emit([&](mavlink_message_t* out) {
    mavlink_msg_current_mode_encode_status(out_.system_id(), out_.component_id(), out_.status(),
                                           out, &m);
  });
}

void TelemetryService::send_heartbeat() {
  mavlink_heartbeat_t hb{};
  hb.type = MAV_TYPE_FIXED_WING;
  hb.autopilot = MAV_AUTOPILOT_GENERIC;
  const bool airborne =
      vehicle_.have_decision && vehicle_.decision.altitude_agl_ft > config_.airborne_agl_ft;
  // custom_mode tells which controller drives the servos (DecisionStatus.CONTROLLER_*, modes.h).
  hb.base_mode =
      heartbeat_base_mode(vehicle_.have_decision, vehicle_.decision.controller, airborne);
  hb.custom_mode = vehicle_.have_decision ? vehicle_.decision.controller : kCustomModeUnknown;
  hb.system_status = airborne ? MAV_STATE_ACTIVE : MAV_STATE_STANDBY;
  if (vehicle_.have_decision && (vehicle_.decision.controller == kControllerHa ||
                                 vehicle_.decision.controller == kControllerHaLatched)) {
    hb.system_status = MAV_STATE_CRITICAL;  // flying on the safety controller
  }
  hb.mavlink_version = 3;
  out_.emit([&](mavlink_message_t* m) {
    mavlink_msg_heartbeat_encode_status(out_.system_id(), out_.component_id(), out_.status(), m,
                                        &hb);
  });
  send_current_mode();  // streamed with the heartbeat (the protocol asks for about 0.5 Hz)
}

void TelemetryService::send_set(const Clock& now) {
  const uint32_t boot_ms = static_cast<uint32_t>(now.mono_ms - boot_ms_);
  const bool fresh =
      vehicle_.have_telemetry && now.mono_ms - vehicle_.telemetry_ms < kTelemetryStaleMs;
  send_sys_status(fresh);
  if (!fresh) return;  // no position or attitude to claim
  send_attitude(boot_ms);
  send_position(boot_ms);
  send_home_position();
  if (missions_.count() > 0) send_mission_current();
  ++counters_.telemetry_sets_sent;
}

void TelemetryService::tick(const Clock& now) {
  if (!started_) {
    started_ = true;
    boot_ms_ = now.mono_ms;
    next_heartbeat_ms_ = now.mono_ms;
    next_set_ms_ = now.mono_ms;
  }
  if (now.mono_ms >= next_heartbeat_ms_) {
    send_heartbeat();
    next_heartbeat_ms_ += kHeartbeatPeriodMs;
    if (next_heartbeat_ms_ <= now.mono_ms) next_heartbeat_ms_ = now.mono_ms + kHeartbeatPeriodMs;
  }
  if (config_.rate_hz > 0.0 && now.mono_ms >= next_set_ms_) {
    send_set(now);
    // Step the schedule by the period (not from now) so the rate holds without drift; after a
    // long stall, restart the schedule instead of bursting.
    const uint64_t period_ms = static_cast<uint64_t>(std::llround(1000.0 / config_.rate_hz));
    next_set_ms_ += std::max<uint64_t>(1, period_ms);
    if (next_set_ms_ <= now.mono_ms) next_set_ms_ = now.mono_ms + period_ms;
  }
}

// The sensors present and, with fresh telemetry, healthy; the battery; the link's bad frames.
void TelemetryService::send_sys_status(bool fresh) {
  const Telemetry& t = vehicle_.telemetry;
  mavlink_sys_status_t s{};
  const uint32_t sensors = MAV_SYS_STATUS_SENSOR_3D_GYRO | MAV_SYS_STATUS_SENSOR_3D_ACCEL |
                           MAV_SYS_STATUS_SENSOR_GPS | MAV_SYS_STATUS_SENSOR_DIFFERENTIAL_PRESSURE |
                           MAV_SYS_STATUS_SENSOR_ABSOLUTE_PRESSURE;
  s.onboard_control_sensors_present = sensors;
  s.onboard_control_sensors_enabled = sensors;
  uint32_t health = 0;
  if (fresh && t.ins_link_up)
    health |=
        MAV_SYS_STATUS_SENSOR_3D_GYRO | MAV_SYS_STATUS_SENSOR_3D_ACCEL | MAV_SYS_STATUS_SENSOR_GPS;
  if (fresh && t.ha_link_up)
    health |= MAV_SYS_STATUS_SENSOR_DIFFERENTIAL_PRESSURE | MAV_SYS_STATUS_SENSOR_ABSOLUTE_PRESSURE;
  // No geofence: neither present nor enabled, and healthy (never breached), as ArduPilot reports
  // it. A ground station that starts out assuming the fence healthy (MAVProxy) would otherwise
  // announce "fence breach" on the first SYS_STATUS.
  s.onboard_control_sensors_health = health | MAV_SYS_STATUS_GEOFENCE;
  s.voltage_battery = fresh ? clamp_u16(t.voltage_v * 1000.0) : UINT16_MAX;
  s.current_battery = -1;
  s.battery_remaining = -1;
  s.errors_comm = clamp_u16(static_cast<double>(counters_.frames_bad_crc % 65535));
  out_.emit([&](mavlink_message_t* m) {
    mavlink_msg_sys_status_encode_status(out_.system_id(), out_.component_id(), out_.status(), m,
                                         &s);
  });
}

void TelemetryService::send_attitude(uint32_t boot_ms) {
  const Telemetry& t = vehicle_.telemetry;
  mavlink_attitude_t a{};
  a.time_boot_ms = boot_ms;
  a.roll = finite_or_zero(t.roll_rad);
  a.pitch = finite_or_zero(t.pitch_rad);
  a.yaw = finite_or_zero(t.yaw_rad);
  a.rollspeed = finite_or_zero(t.p_radps);
  a.pitchspeed = finite_or_zero(t.q_radps);
  a.yawspeed = finite_or_zero(t.r_radps);
  out_.emit([&](mavlink_message_t* m) {
    mavlink_msg_attitude_encode_status(out_.system_id(), out_.component_id(), out_.status(), m, &a);
  });
}

// GLOBAL_POSITION_INT, VFR_HUD and GPS_RAW_INT from the INS's solution.
void TelemetryService::send_position(uint32_t boot_ms) {
  const Telemetry& t = vehicle_.telemetry;
  const double ground_mps = std::hypot(t.v_north_mps, t.v_east_mps);
  const double hdg_deg = heading_deg(t.yaw_rad);
  const bool position_ok = is_valid_position(t.lat_deg, t.lon_deg) && std::isfinite(t.alt_m);

  mavlink_global_position_int_t g{};
  g.time_boot_ms = boot_ms;
  g.lat = clamp_i32(t.lat_deg * 1e7);
  g.lon = clamp_i32(t.lon_deg * 1e7);
  g.alt = clamp_i32(t.alt_m * 1000.0);  // ellipsoid height: the INS gives no geoid separation
  g.relative_alt = vehicle_.home_known ? clamp_i32((t.alt_m - vehicle_.home.alt_m) * 1000.0) : 0;
  g.vx = clamp_i16(t.v_north_mps * 100.0);
  g.vy = clamp_i16(t.v_east_mps * 100.0);
  g.vz = clamp_i16(t.v_down_mps * 100.0);
  g.hdg = clamp_u16(hdg_deg * 100.0);
  out_.emit([&](mavlink_message_t* m) {
    mavlink_msg_global_position_int_encode_status(out_.system_id(), out_.component_id(),
                                                  out_.status(), m, &g);
  });

  mavlink_vfr_hud_t v{};
  v.airspeed = finite_or_zero(t.airspeed_ftps / kFeetPerMetre);
  v.groundspeed = finite_or_zero(ground_mps);
  v.heading = static_cast<int16_t>(hdg_deg);
  v.throttle = clamp_u16(std::max(0.0, std::min(1.0, t.throttle)) * 100.0);
  v.alt = finite_or_zero(t.alt_m);
  v.climb = finite_or_zero(-t.v_down_mps);
  out_.emit([&](mavlink_message_t* m) {
    mavlink_msg_vfr_hud_encode_status(out_.system_id(), out_.component_id(), out_.status(), m, &v);
  });

  mavlink_gps_raw_int_t r{};
  r.time_usec = static_cast<uint64_t>(boot_ms) * 1000u;
  r.fix_type = position_ok && t.ins_link_up ? GPS_FIX_TYPE_3D_FIX : GPS_FIX_TYPE_NO_FIX;
  r.lat = g.lat;
  r.lon = g.lon;
  r.alt = g.alt;
  r.eph = UINT16_MAX;
  r.epv = UINT16_MAX;
  r.vel = clamp_u16(ground_mps * 100.0);
  r.cog = clamp_u16(
      std::fmod(std::atan2(t.v_east_mps, t.v_north_mps) * 180.0 / kPi + 360.0, 360.0) * 100.0);
  r.satellites_visible = 255;  // unknown: /data does not carry it
  out_.emit([&](mavlink_message_t* m) {
    mavlink_msg_gps_raw_int_encode_status(out_.system_id(), out_.component_id(), out_.status(), m,
                                          &r);
  });
}

// The mission item the controller flies to, in the GCS's numbering.
void TelemetryService::send_mission_current() {
  const Telemetry& t = vehicle_.telemetry;
  mavlink_mission_current_t c{};
  // The controller counts the waypoints on /way; the GCS counts mission items (home, speeds).
  const int32_t wp =
      std::max<int32_t>(0, std::min<int32_t>(t.waypoint_index, missions_.plan().fp - 1));
  c.seq = static_cast<uint16_t>(missions_.plan().fp > 0 ? missions_.plan().item_seq[wp] : 0);
  c.total = static_cast<uint16_t>(missions_.count());
  c.mission_state = MISSION_STATE_ACTIVE;
  c.mission_mode = t.computer_in_command ? 1 : 2;
  out_.emit([&](mavlink_message_t* m) {
    mavlink_msg_mission_current_encode_status(out_.system_id(), out_.component_id(), out_.status(),
                                              m, &c);
  });
}

}  // namespace microhard_gs
