#include "node_config.h"

#include <ros/param.h>

#include <cmath>
#include <ctime>
#include <fstream>
#include <sstream>

#include "limits_ranges.h"
#include "serial_transport.h"

namespace microhard_gs {
namespace {

bool need(const ros::NodeHandle& nh, const std::string& name, double* out, std::string* error) {
  if (!nh.getParam(name, *out) || !std::isfinite(*out)) {
    *error = "missing or non-numeric parameter " + nh.resolveName(name);
    return false;
  }
  return true;
}

bool in_range(const std::string& name, double v, double lo, double hi, std::string* error) {
  if (!(v >= lo && v <= hi)) {  // written so that NaN fails too
    std::ostringstream s;
    s << name << " = " << v << " outside [" << lo << ", " << hi << "]";
    *error = s.str();
    return false;
  }
  return true;
}

// A limits.yaml key, in the range every component accepts (aircraft/limits_ranges.yaml).
bool need_limit(const ros::NodeHandle& nh, const limits_ranges::Range& range, double* out,
                std::string* error) {
  const std::string name = std::string("limits/") + range.key;
  return need(nh, name, out, error) && in_range(name, *out, range.min, range.max, error);
}

// Fills the path's strftime fields (%Y-%m-%d_%H%M%S) with the local time, as record_flight
// names the bag, so a flight launch can put the tlog beside it under the same kind of name.
bool expand_time_fields(const std::string& pattern, std::string* out, std::string* error) {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  char buf[4096];
  const size_t n = std::strftime(buf, sizeof buf, pattern.c_str(), &local);
  if (n == 0) {
    *error = "tlog_path " + pattern + " is too long once its time fields are filled in";
    return false;
  }
  *out = std::string(buf, n);
  return true;
}

// The ground link: transport, ports, the tlog, the node's MAVLink identity and timeouts.
bool read_link(const ros::NodeHandle& nh, NodeConfig* c, std::string* error) {
  nh.param<std::string>("transport", c->transport, "udp");
  nh.param<std::string>("udp_bind_address", c->udp.bind_address, "0.0.0.0");
  nh.param("udp_bind_port", c->udp.bind_port, 14555);
  nh.param<std::string>("udp_remote_address", c->udp.remote_address, "127.0.0.1");
  nh.param("udp_remote_port", c->udp.remote_port, 14550);  // QGroundControl listens here
  nh.param("udp_follow_sender", c->udp.follow_sender, true);
  nh.param<std::string>("serial_port", c->serial_port, "/dev/ttyUSB0");
  nh.param("serial_baud", c->serial_baud, 57600);
  // Defaults are those of the structs (node_config.h, gs_core.h), stated once.
  nh.param("reopen_period_s", c->reopen_period_s, c->reopen_period_s);
  double param_set_timeout_s = c->core.param_set_timeout_ms / 1000.0;
  nh.param("param_set_timeout_s", param_set_timeout_s, param_set_timeout_s);
  nh.param<std::string>("signing_key_file", c->signing_key_file, "");
  // The controller loads its tunables (aircraft/<name>/controller_param.yaml) into its private
  // namespace; the thesis kept them in /controller_param.
  nh.param<std::string>("controller_param_ns", c->controller_param_ns, "controller_DG808");
  int system_id = 1;
  nh.param("system_id", system_id, 1);
  std::string tlog_pattern;
  nh.param<std::string>("tlog_path", tlog_pattern, "");

  if (c->transport != "udp" && c->transport != "serial") {
    *error = "transport must be udp or serial, not " + c->transport;
    return false;
  }
  if (c->transport == "serial" && !SerialTransport::is_supported_baud(c->serial_baud)) {
    *error = "serial_baud " + std::to_string(c->serial_baud) + " not supported";
    return false;
  }
  // Fast enough that telemetry resumes soon after the modem is back, slow enough that a missing
  // port costs nothing; the HA and INS links retry at the same order.
  if (!in_range("reopen_period_s", c->reopen_period_s, 0.05, 60.0, error)) return false;
  if (!in_range("system_id", system_id, 1, 254, error)) return false;
  // The controller answers in milliseconds; the ceiling stays under the second or so a GCS
  // waits for the echo (QGroundControl then resends the PARAM_SET).
  if (!in_range("param_set_timeout_s", param_set_timeout_s, 0.05, 1.0, error)) return false;
  if (!tlog_pattern.empty()) {
    // A node started by roslaunch runs in ROS_HOME: a relative path would land there unseen.
    if (tlog_pattern.front() != '/' || tlog_pattern.back() == '/') {
      *error = "tlog_path must be an absolute file path (or empty: no tlog), not " + tlog_pattern;
      return false;
    }
    if (!expand_time_fields(tlog_pattern, &c->tlog_path, error)) return false;
    c->core.keep_received_frames = true;
  }
  c->core.param_set_timeout_ms = static_cast<uint32_t>(std::lround(param_set_timeout_s * 1000.0));
  c->core.system_id = static_cast<uint8_t>(system_id);
  return true;
}

// The telemetry rate and what a mission may ask, inside the aircraft's limits.
bool read_mission_limits(const ros::NodeHandle& nh, NodeConfig* c, std::string* error) {
  double rate_hz = 0, floor_ft = 0, radius_ft = 0, speed_ftps = 0, timeout_s = 0, retries = 0;
  double ceiling_ft = 0, stall_ftps = 0, airborne_ft = 0;
  if (!need(nh, "telemetry_rate_hz", &rate_hz, error) ||
      !need(nh, "mission/floor_agl_ft", &floor_ft, error) ||
      !need(nh, "mission/max_radius_ft", &radius_ft, error) ||
      !need(nh, "mission/default_speed_ftps", &speed_ftps, error) ||
      !need(nh, "mission/item_timeout_s", &timeout_s, error) ||
      !need(nh, "mission/max_retries", &retries, error) ||
      !need_limit(nh, limits_ranges::kStateCeilingAglFt, &ceiling_ft, error) ||
      !need_limit(nh, limits_ranges::kStateStallSpeedFtps, &stall_ftps, error) ||
      !need_limit(nh, limits_ranges::kStateAirborneAglFt, &airborne_ft, error)) {
    return false;
  }
  if (!in_range("telemetry_rate_hz", rate_hz, 0.5, 100.0, error) ||
      !in_range("mission/floor_agl_ft", floor_ft, 0.0, ceiling_ft, error) ||
      !in_range("mission/max_radius_ft", radius_ft, 100.0, 100000.0, error) ||
      !in_range("mission/default_speed_ftps", speed_ftps, stall_ftps, 500.0, error) ||
      !in_range("mission/item_timeout_s", timeout_s, 0.05, 30.0, error) ||
      !in_range("mission/max_retries", retries, 0.0, 50.0, error)) {
    return false;
  }
  c->core.telemetry_rate_hz = rate_hz;
  c->core.mission.limits.floor_ft = floor_ft;
  c->core.mission.limits.ceiling_ft = ceiling_ft;
  c->core.mission.limits.max_radius_ft = radius_ft;
  c->core.mission.limits.min_speed_ftps = stall_ftps;
  c->core.mission.limits.default_speed_ftps = speed_ftps;
  c->core.airborne_agl_ft = airborne_ft;
  c->core.mission.item_timeout_ms = static_cast<uint32_t>(std::lround(timeout_s * 1000.0));
  c->core.mission.max_retries = static_cast<uint32_t>(std::lround(retries));
  return true;
}

// The MAVLink 2 signing key, when a file names one.
bool read_signing_key(NodeConfig* c, std::string* error) {
  if (c->signing_key_file.empty()) return true;
  std::ifstream in(c->signing_key_file);
  if (!in) {
    *error = "cannot read signing_key_file " + c->signing_key_file;
    return false;
  }
  std::stringstream text;
  text << in.rdbuf();
  std::string why;
  if (!parse_signing_key(text.str(), &c->core.signing_key, &why)) {
    *error = c->signing_key_file + ": " + why;
    return false;
  }
  c->core.signing = true;
  return true;
}

// The tunables: whatever of the known set the controller's namespace holds.
void read_tunables(NodeConfig* c) {
  for (const ParamSpec& spec : controller_param_specs()) {
    const std::string key = c->controller_param_ns + "/" + spec.ros_name;
    double value = 0.0;
    int ivalue = 0;
    bool bvalue = false;
    if (ros::param::get(key, value)) {
      c->params.add(spec, value);
    } else if (ros::param::get(key, ivalue)) {
      c->params.add(spec, ivalue);
    } else if (ros::param::get(key, bvalue)) {
      c->params.add(spec, bvalue ? 1.0 : 0.0);
    } else {
      c->missing_params.push_back(spec.ros_name);
    }
  }
}

}  // namespace

bool read_node_config(const ros::NodeHandle& nh, NodeConfig* c, std::string* error) {
  if (!read_link(nh, c, error) || !read_mission_limits(nh, c, error)) return false;
  // A second home would build /way about a point the controller and the HA do not fly about:
  // the one home is the HA's, on /home. A settings file that still names one is refused.
  if (nh.hasParam("home")) {
    *error =
        "home/... is gone: the ground station takes the HA's home from /home (set it from "
        "QGroundControl with MAV_CMD_DO_SET_HOME while parked)";
    return false;
  }
  if (!read_signing_key(c, error)) return false;
  read_tunables(c);
  return true;
}

}  // namespace microhard_gs
