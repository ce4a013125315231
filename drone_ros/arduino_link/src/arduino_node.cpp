// The `arduino` node: the HP end of the rosserial link to the Due (see arduino_link_node.h).
#include <ros/ros.h>

#include "arduino_link_node.h"
#include "link_params.h"

int main(int argc, char **argv) {
  ros::init(argc, argv, "arduino");
  ros::NodeHandle nh;
  ros::NodeHandle pnh("~");
  arduino_link::LinkParams params;
  std::string error;
  if (!arduino_link::read_link_params(pnh, &params, &error)) {
    ROS_FATAL("arduino: %s", error.c_str());
    return 2;
  }
  arduino_link::ArduinoLinkNode node(nh, pnh, params);
  node.run();
  return 0;
}
