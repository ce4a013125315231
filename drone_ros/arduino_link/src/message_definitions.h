// The message types this package knows at compile time. A device topic is published generically
// from its announced type and md5sum; when the type is one of these, the node also has its full
// definition (the text rosbag stores with each connection, so bags recorded from
// /decision_status and friends can be read back by tools) and can check that a payload really
// is such a message before passing it on. Unknown types get an empty definition (ROS warns
// once) and are passed on unchecked: the node cannot know their layout.
#ifndef ARDUINO_LINK_MESSAGE_DEFINITIONS_H
#define ARDUINO_LINK_MESSAGE_DEFINITIONS_H

#include <cstddef>
#include <cstdint>
#include <string>

namespace arduino_link {

struct KnownType {
  std::string definition;
  // True if data[0..size) is exactly one serialized message of this type, nothing left over.
  bool (*decodes)(const uint8_t *data, std::size_t size);
};

// The known type `type` if its md5sum matches the compiled one, else nullptr. The pointer stays
// valid for the life of the process.
const KnownType *find_known_type(const std::string &type, const std::string &md5);

}  // namespace arduino_link

#endif
