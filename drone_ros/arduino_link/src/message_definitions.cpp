#include "message_definitions.h"

#include <drone_ros/DecisionStatus.h>
#include <drone_ros/OperatorCommand.h>
#include <drone_ros/ServoCommand.h>
#include <drone_ros/pwm.h>
#include <std_msgs/Time.h>

namespace arduino_link {

namespace {
template <typename M>
bool match(const std::string &type, const std::string &md5, std::string *definition) {
  if (type != ros::message_traits::DataType<M>::value() || md5 != ros::message_traits::MD5Sum<M>::value()) {
    return false;
  }
  *definition = ros::message_traits::Definition<M>::value();
  return true;
}
}  // namespace

std::string known_definition(const std::string &type, const std::string &md5) {
  std::string d;
  if (match<drone_ros::DecisionStatus>(type, md5, &d) || match<drone_ros::pwm>(type, md5, &d) ||
      match<drone_ros::ServoCommand>(type, md5, &d) || match<drone_ros::OperatorCommand>(type, md5, &d) ||
      match<std_msgs::Time>(type, md5, &d)) {
    return d;
  }
  return std::string();
}

}  // namespace arduino_link
