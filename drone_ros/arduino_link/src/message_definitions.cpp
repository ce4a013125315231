#include "message_definitions.h"

#include <drone_ros/DecisionStatus.h>
#include <drone_ros/HomePosition.h>
#include <drone_ros/OperatorCommand.h>
#include <drone_ros/ServoCommand.h>
#include <drone_ros/pwm.h>
#include <ros/serialization.h>
#include <std_msgs/Bool.h>
#include <std_msgs/Float32.h>
#include <std_msgs/Int32.h>
#include <std_msgs/String.h>
#include <std_msgs/Time.h>

#include <limits>

namespace arduino_link {

namespace {

template <typename M>
bool decodes(const uint8_t *data, std::size_t size) {
  if (size > std::numeric_limits<uint32_t>::max()) return false;
  M msg;
  try {
    // IStream only reads, despite the non-const pointer it takes.
    ros::serialization::IStream in(const_cast<uint8_t *>(data), static_cast<uint32_t>(size));
    ros::serialization::deserialize(in, msg);
    return in.getLength() == 0;  // trailing bytes: not one message of this type
  } catch (const ros::Exception &) {
    return false;
  }
}

struct Entry {
  std::string type, md5;
  KnownType known;
};

template <typename M>
Entry entry() {
  return Entry{ros::message_traits::DataType<M>::value(), ros::message_traits::MD5Sum<M>::value(),
               KnownType{ros::message_traits::Definition<M>::value(), &decodes<M>}};
}

}  // namespace

const KnownType *find_known_type(const std::string &type, const std::string &md5) {
  // The HA's own types, and the std_msgs a stock rosserial_arduino sketch is most likely to use.
  static const Entry kKnown[] = {
      entry<drone_ros::DecisionStatus>(), entry<drone_ros::pwm>(),
      entry<drone_ros::ServoCommand>(),   entry<drone_ros::OperatorCommand>(),
      entry<drone_ros::HomePosition>(),   entry<std_msgs::Time>(),
      entry<std_msgs::String>(),          entry<std_msgs::Float32>(),
      entry<std_msgs::Int32>(),           entry<std_msgs::Bool>(),
  };
  for (const Entry &e : kKnown) {
    if (e.type == type && e.md5 == md5) return &e.known;
  }
  return nullptr;
}

}  // namespace arduino_link
