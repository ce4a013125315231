#include <drone_ros_common/node_main.h>
#include <ros/ros.h>

#include "node_params.h"
#include "vn200_node.h"

int main(int argc, char** argv) {
  return drone_ros_common::node_main<vn200::NodeParams>(
      argc, argv, "vn200", vn200::load_params,
      [](ros::NodeHandle& nh, ros::NodeHandle& pnh, const vn200::NodeParams& params) {
        vn200::Vn200Node node(nh, pnh, params);
        return node.run();
      });
}
