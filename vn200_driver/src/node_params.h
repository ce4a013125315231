// Every private parameter of the vn200 node, read and validated in one place.
#pragma once

#include <ros/node_handle.h>

#include <cstdint>
#include <string>

#include "packet_messages.h"

namespace vn200 {

struct NodeParams {
  std::string port = "/dev/ttyUSB0";  // the HP's USB link to the VN-200 (its serial port 2)
  int baud = 921600;
  int sensor_baud = 0;  // the sensor's speed at power-up if not `baud` (factory:
                        // 115200): each connect switches it to `baud` (register 5)
  int rate_hz = 100;    // binary output rate: 800 Hz / integer divisor
  int sensor_port = 2;  // which VN-200 serial port the HP is wired to (1 or 2)
  // Which of the sensor's three binary outputs (registers 75-77) the node writes. They are
  // global to the sensor, each routed to a port by its AsyncMode: Binary Output 1 belongs to the
  // HA on port 1, so the HP must never rewrite it, or it could silence the trusted side's INS.
  int binary_output = 2;
  std::string frame_id = "vn200";  // the sensor's frame, REP-103 (x forward, y left, z up)
  std::string frd_frame_id =
      "vn200_frd";  // the sensor's frame as it reports (x fwd, y right, z down)
  // REP-105: map is ENU at home (the HA's /home); odom is map itself (a GPS-aided INS does not
  // drift, so there is no jump for odom to hide); base_link is the airframe, the sensor on its
  // mount (~mount/*, aircraft/<name>/vn200_mount.yaml).
  std::string map_frame_id = "map";
  std::string odom_frame_id = "odom";
  std::string base_frame_id = "base_link";
  SensorMount mount;
  std::string replay_file;    // non-empty: read this capture instead of the port
  double replay_speed = 1.0;  // replay pacing: 1 = sensor time, 2 = twice as fast
  bool replay_loop = false;
  double replay_delay_s = 0.0;               // wait before replaying, so subscribers can connect
  bool replay_wait_for_subscribers = false;  // and then until every data topic has one
  double reconnect_period_s = 1.0;           // between attempts to reopen a lost port
  double data_timeout_s = 1.0;               // silence after which the link is reported down
  double response_timeout_s = 0.5;           // per configuration command
  bool publish_tf = true;
};

// Reads ~parameters; returns false with a message naming the bad parameter.
bool load_params(const ros::NodeHandle& pnh, NodeParams* out, std::string* error);

}  // namespace vn200
