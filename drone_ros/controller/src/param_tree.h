// The controller's private parameters from one fetch of its whole namespace.
#ifndef CONTROLLER_PARAM_TREE_H
#define CONTROLLER_PARAM_TREE_H

#include <XmlRpcValue.h>

#include <string>

namespace controller {

// The number at key ("limits/actuators/aileron_limit_deg") in tree, the struct the master returns
// for a namespace. An int or a bool counts as a number, as ros::param::get reads them; false if a
// level is missing or not a struct, or the leaf is not one of the three.
//
// Why one fetch: the controller reads 113 values, and each getParam is a round trip to the Python
// master. A restarted controller's start is on the HP's way back to the servos (and, in lockstep,
// time stands meanwhile).
bool number_at(XmlRpc::XmlRpcValue &tree, const std::string &key, double *value);

}  // namespace controller

#endif  // CONTROLLER_PARAM_TREE_H
