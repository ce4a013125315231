// Full message definitions (the text rosbag stores with each connection) for the types this
// package knows at compile time. A device topic is published generically from its announced
// type and md5sum; the definition is looked up here so bags recorded from /decision_status and
// friends can be read back by tools. Unknown types get an empty definition (ROS warns once).
#ifndef ARDUINO_LINK_MESSAGE_DEFINITIONS_H
#define ARDUINO_LINK_MESSAGE_DEFINITIONS_H

#include <string>

namespace arduino_link {

// The definition of `type` if its md5sum matches the compiled one, else "".
std::string known_definition(const std::string &type, const std::string &md5);

}  // namespace arduino_link

#endif
