// Every node's main(): its private parameters are read and validated in one place before anything
// opens a port or advertises, and a bad one ends the node with exit status 2 and the parameter
// named (a node launched required="true" then ends the launch with the reason on screen).
#pragma once

#include "drone_ros_common/xmlrpc_wake.h"

#include <ros/ros.h>

#include <stdexcept>
#include <string>
#include <utility>

namespace drone_ros_common {

// load(pnh, &params, &error) reads and validates; run(nh, pnh, params) is the node's life and
// returns its exit status.
template <class Params, class Load, class Run>
int node_main(int argc, char **argv, const std::string &name, Load load, Run run) {
  ros::init(argc, argv, name);
  ros::NodeHandle nh;
  ros::NodeHandle pnh("~");
  try {
    XmlRpcWake::install(kXmlRpcWakePeriodS);
  } catch (const std::runtime_error &e) {
    ROS_FATAL("%s: %s", name.c_str(), e.what());
    return 1;
  }
  Params params{};
  std::string error;
  if (!load(pnh, &params, &error)) {
    ROS_FATAL("%s: bad parameter: %s", name.c_str(), error.c_str());
    return 2;
  }
  return run(nh, pnh, std::move(params));
}

}  // namespace drone_ros_common
