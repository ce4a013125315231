#include "node_params.h"

#include <cmath>
#include <set>

#include "output_config.h"
#include "vn_command.h"

namespace vn200 {
namespace {

// Every private parameter, over the defaults NodeParams holds.
void read_params(const ros::NodeHandle& pnh, NodeParams* p) {
  pnh.param("port", p->port, p->port);
  pnh.param("baud", p->baud, p->baud);
  pnh.param("sensor_baud", p->sensor_baud, p->sensor_baud);
  pnh.param("rate_hz", p->rate_hz, p->rate_hz);
  pnh.param("sensor_port", p->sensor_port, p->sensor_port);
  pnh.param("binary_output", p->binary_output, p->binary_output);
  pnh.param("frame_id", p->frame_id, p->frame_id);
  pnh.param("frd_frame_id", p->frd_frame_id, p->frd_frame_id);
  pnh.param("map_frame_id", p->map_frame_id, p->map_frame_id);
  pnh.param("odom_frame_id", p->odom_frame_id, p->odom_frame_id);
  pnh.param("base_frame_id", p->base_frame_id, p->base_frame_id);
  pnh.param("mount/x_m", p->mount.x_m, p->mount.x_m);
  pnh.param("mount/y_m", p->mount.y_m, p->mount.y_m);
  pnh.param("mount/z_m", p->mount.z_m, p->mount.z_m);
  pnh.param("mount/roll_deg", p->mount.roll_deg, p->mount.roll_deg);
  pnh.param("mount/pitch_deg", p->mount.pitch_deg, p->mount.pitch_deg);
  pnh.param("mount/yaw_deg", p->mount.yaw_deg, p->mount.yaw_deg);
  pnh.param("replay_file", p->replay_file, p->replay_file);
  pnh.param("replay_speed", p->replay_speed, p->replay_speed);
  pnh.param("replay_loop", p->replay_loop, p->replay_loop);
  pnh.param("replay_delay_s", p->replay_delay_s, p->replay_delay_s);
  pnh.param("replay_wait_for_subscribers", p->replay_wait_for_subscribers,
            p->replay_wait_for_subscribers);
  pnh.param("reconnect_period_s", p->reconnect_period_s, p->reconnect_period_s);
  pnh.param("data_timeout_s", p->data_timeout_s, p->data_timeout_s);
  pnh.param("response_timeout_s", p->response_timeout_s, p->response_timeout_s);
  pnh.param("publish_tf", p->publish_tf, p->publish_tf);
}

// The port, its rates and the sensor's output: what the sensor can be configured to send.
bool check_serial(const NodeParams* p, std::string* error) {
  const bool replay = !p->replay_file.empty();
  if (!replay && p->port.empty()) {
    *error = "~port is empty and no ~replay_file is given";
    return false;
  }
  // Every rate the VN-200 offers, 128000 included: the shared serial port sets rates termios has
  // no constant for through termios2.
  if (p->baud <= 0 || !vn_baud_supported(static_cast<uint32_t>(p->baud))) {
    *error = "~baud " + std::to_string(p->baud) +
             " is not one of 9600, 19200, 38400, 57600, 115200, 128000, 230400, 460800, 921600";
    return false;
  }
  if (p->sensor_baud != 0 &&
      (p->sensor_baud < 0 || !vn_baud_supported(static_cast<uint32_t>(p->sensor_baud)))) {
    *error = "~sensor_baud " + std::to_string(p->sensor_baud) +
             " is not 0 (sensor already at ~baud) or a baud rate the node supports";
    return false;
  }
  if (p->rate_hz <= 0 || !rate_supported(static_cast<unsigned>(p->rate_hz))) {
    *error = "~rate_hz " + std::to_string(p->rate_hz) + " must divide 800 Hz evenly";
    return false;
  }
  if (p->sensor_port != 1 && p->sensor_port != 2) {
    *error = "~sensor_port must be 1 or 2";
    return false;
  }
  if (p->binary_output < 1 || p->binary_output > 3) {
    *error = "~binary_output must be 1, 2 or 3 (registers 75-77)";
    return false;
  }
  if (p->binary_output == 1 && p->sensor_port != 1) {
    *error = "~binary_output 1 (register 75) is the HA's, on the sensor's port 1; the HP on port " +
             std::to_string(p->sensor_port) + " uses 2 or 3";
    return false;
  }
  const VnBinaryOutputConfig cfg = node_output_config(static_cast<unsigned>(p->rate_hz),
                                                      static_cast<VnAsyncMode>(p->sensor_port),
                                                      static_cast<unsigned>(p->binary_output));
  if (!replay && stream_bits_per_second(cfg, static_cast<unsigned>(p->rate_hz)) > p->baud) {
    *error = "~rate_hz " + std::to_string(p->rate_hz) + " needs more than ~baud " +
             std::to_string(p->baud) + " carries (the sensor would answer $VNERR 12)";
    return false;
  }
  return true;
}

// One tf tree, and a mount on the airframe.
bool check_frames_and_mount(const NodeParams* p, std::string* error) {
  const std::set<std::string> frames{p->frame_id, p->frd_frame_id, p->map_frame_id,
                                     p->odom_frame_id, p->base_frame_id};
  if (frames.size() != 5 || frames.count("") != 0) {
    *error =
        "~frame_id, ~frd_frame_id, ~map_frame_id, ~odom_frame_id and ~base_frame_id must be "
        "five different, non-empty names (one tf tree)";
    return false;
  }
  // A lever arm beyond the airframe is a unit slip (mm for m), not a mount.
  const SensorMount& m = p->mount;
  for (const double arm : {m.x_m, m.y_m, m.z_m}) {
    if (!std::isfinite(arm) || std::fabs(arm) > 10.0) {
      *error = "~mount/x_m, y_m, z_m must be finite and within 10 m of base_link";
      return false;
    }
  }
  if (!(std::fabs(m.roll_deg) <= 180.0) || !(std::fabs(m.pitch_deg) <= 90.0) ||
      !(std::fabs(m.yaw_deg) <= 180.0)) {
    *error = "~mount/roll_deg and yaw_deg must be within +-180, pitch_deg within +-90";
    return false;
  }
  return true;
}

bool check_timing(const NodeParams* p, std::string* error) {
  if (!(p->replay_speed > 0.0) || !(p->reconnect_period_s > 0.0) || !(p->data_timeout_s > 0.0) ||
      !(p->response_timeout_s > 0.0) || !(p->replay_delay_s >= 0.0)) {
    *error =
        "~replay_speed, ~reconnect_period_s, ~data_timeout_s, ~response_timeout_s must be > 0 "
        "and ~replay_delay_s >= 0";
    return false;
  }
  return true;
}

}  // namespace

bool load_params(const ros::NodeHandle& pnh, NodeParams* p, std::string* error) {
  read_params(pnh, p);
  return check_serial(p, error) && check_frames_and_mount(p, error) && check_timing(p, error);
}

}  // namespace vn200
