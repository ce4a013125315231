// The payloads of rosserial's reserved topics as the host reads and writes them (TopicInfo
// announcements, device logs, parameter requests and replies), free of ROS so they can be fuzzed
// and tested alone. Everything a device sends is checked here before the node lets ROS see it:
// roscpp throws (and would abort the node) on a topic name, type or md5sum it does not accept.
// The topic name's ROS syntax is checked by the node with ros::names::validate, the one
// authority on it; what can be checked without ROS is checked here.
#ifndef ARDUINO_LINK_DEVICE_PAYLOADS_H
#define ARDUINO_LINK_DEVICE_PAYLOADS_H

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace arduino_link {

// rosserial reserves topic ids below this for itself (TopicInfo's ID_* constants); ros_lib
// numbers subscribers from 100 and publishers from 100 + MAX_SUBSCRIBERS.
constexpr uint16_t kFirstUserTopicId = 100;

// A device's rosserial_msgs/TopicInfo: one publisher or subscriber it wants on the ROS side.
struct TopicAnnouncement {
  uint16_t topic_id = 0;
  std::string name, type, md5;
  int32_t buffer_size = 0;
};

// Decodes a TopicInfo payload and checks what ROS would refuse: the whole payload used, a user
// topic id, a non-empty name, a type "package/Message", a 32-hex-digit md5sum. False (with the
// reason in *why) for anything else.
bool decode_topic_announcement(const std::vector<uint8_t> &payload, TopicAnnouncement *out,
                               std::string *why);

// "package/Message" with both parts legal ROS resource names (a letter, then letters, digits, _).
bool is_message_type(const std::string &type);
// 32 lowercase or uppercase hex digits, as genmsg writes them.
bool is_md5sum(const std::string &md5);

// A device's rosserial_msgs/Log.
struct DeviceLog {
  uint8_t level = 0;
  std::string text;
};
bool decode_device_log(const std::vector<uint8_t> &payload, DeviceLog *out);

// A device's rosserial_msgs/RequestParam request: the parameter's name.
bool decode_param_request(const std::vector<uint8_t> &payload, std::string *name);

// The reply: a parameter's values by type (a bool travels as an int, as rosserial does).
struct ParamValues {
  std::vector<int32_t> ints;
  std::vector<float> floats;
  std::vector<std::string> strings;
};
// The most values per type a reply may carry: the Due's generated code holds no more, and the
// node serves every device the same.
std::size_t max_param_values_per_type();
// Serializes the reply; false (with the reason in *why) if it holds more values per type than the
// limit or does not fit max_payload bytes. An empty ParamValues is the "not set" reply.
bool encode_param_reply(const ParamValues &values, std::size_t max_payload,
                        std::vector<uint8_t> *payload, std::string *why);

}  // namespace arduino_link

#endif
