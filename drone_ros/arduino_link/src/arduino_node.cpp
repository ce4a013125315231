// The `arduino` node: the HP end of the rosserial link to the Due (see arduino_link_node.h).
#include <drone_ros_common/node_main.h>
#include <ros/ros.h>

#include "arduino_link_node.h"
#include "link_params.h"

int main(int argc, char **argv) {
  return drone_ros_common::node_main<arduino_link::LinkParams>(
      argc, argv, "arduino", arduino_link::read_link_params,
      [](ros::NodeHandle &nh, ros::NodeHandle &pnh, const arduino_link::LinkParams &params) {
        arduino_link::ArduinoLinkNode node(nh, pnh, params);
        node.run();
        return 0;
      });
}
