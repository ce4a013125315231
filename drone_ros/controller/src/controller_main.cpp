// controller_<aircraft> entry point: load and validate parameters, then spin.
#include <drone_ros_common/node_main.h>
#include <ros/ros.h>

#include "controller_node.h"

namespace {

struct Loaded {
  controller::ControllerParams params;
  controller::ParamValues values;  // the base later tunable changes are checked against
  std::string frame_id;
};

bool load(const ros::NodeHandle &pnh, Loaded *out, std::string *error) {
  return controller::load_params(pnh, &out->params, &out->values, &out->frame_id, error);
}

}  // namespace

int main(int argc, char **argv) {
  return drone_ros_common::node_main<Loaded>(
      argc, argv, std::string("controller_") + GNC_AIRCRAFT_NAME, load,
      [](ros::NodeHandle &nh, ros::NodeHandle &pnh, const Loaded &l) {
        controller::ControllerNode node(nh, pnh, l.params, l.values, l.frame_id);
        ros::spin();
        return 0;
      });
}
