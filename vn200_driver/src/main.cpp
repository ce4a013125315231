#include <ros/ros.h>

#include "node_params.h"
#include "vn200_node.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "vn200");
  ros::NodeHandle nh;
  ros::NodeHandle pnh("~");
  vn200::NodeParams params;
  std::string error;
  if (!vn200::load_params(pnh, &params, &error)) {
    ROS_FATAL("vn200: bad parameter: %s", error.c_str());
    return 2;
  }
  vn200::Vn200Node node(nh, pnh, params);
  return node.run();
}
