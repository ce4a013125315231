// controller_<aircraft> entry point: load and validate parameters, then spin.
#include <ros/ros.h>

#include "controller_node.h"

int main(int argc, char **argv) {
  ros::init(argc, argv, std::string("controller_") + GNC_AIRCRAFT_NAME);
  ros::NodeHandle nh;
  ros::NodeHandle pnh("~");
  controller::ControllerParams params;
  controller::ParamValues values;
  std::string frame_id;
  std::string error;
  if (!controller::load_params(pnh, &params, &values, &frame_id, &error)) {
    ROS_FATAL("controller_%s: bad parameter: %s", GNC_AIRCRAFT_NAME, error.c_str());
    return 1;
  }
  controller::ControllerNode node(nh, pnh, params, values, frame_id);
  ros::spin();
  return 0;
}
