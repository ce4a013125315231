// Every parameter of the microhard_gs node, read and validated in one place.
#pragma once

#include <ros/node_handle.h>

#include <string>
#include <vector>

#include "gs_core.h"
#include "params.h"
#include "udp_transport.h"

namespace microhard_gs {

struct NodeConfig {
  std::string transport;  // "udp" or "serial"
  UdpConfig udp;
  std::string serial_port;
  int serial_baud = 0;
  double reopen_period_s = 1.0;  // serial: how often a missing or unplugged modem port is retried
  std::string signing_key_file;
  std::string controller_param_ns;
  // The MAVLink telemetry log (.tlog): absolute, its strftime fields filled in with the local
  // time at start; empty: none.
  std::string tlog_path;
  GsConfig core;
  ParamTable params;
  std::vector<std::string> missing_params;  // tunables absent from the parameter server
};

// Reads ~ parameters (the launch file loads aircraft/<name>/ground_station.yaml into ~ and
// aircraft/<name>/limits.yaml into ~limits). False and `error` set on anything missing or out
// of range; the node then refuses to start.
bool read_node_config(const ros::NodeHandle& private_nh, NodeConfig* config, std::string* error);

}  // namespace microhard_gs
