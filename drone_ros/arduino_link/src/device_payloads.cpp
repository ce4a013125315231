#include "device_payloads.h"

#include "ha_link_msgs.h"

namespace arduino_link {

namespace {

std::string to_string(const HaRosString &s) { return std::string(s.data, s.len); }

bool is_alpha(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }
bool is_digit(char c) { return c >= '0' && c <= '9'; }

// genmsg's legal base name: a letter, then letters, digits or underscores.
bool is_base_name(const std::string &s, std::size_t begin, std::size_t end) {
  if (begin >= end || !is_alpha(s[begin])) return false;
  for (std::size_t i = begin + 1; i < end; ++i) {
    if (!is_alpha(s[i]) && !is_digit(s[i]) && s[i] != '_') return false;
  }
  return true;
}

}  // namespace

bool is_message_type(const std::string &type) {
  const std::size_t slash = type.find('/');
  return slash != std::string::npos && is_base_name(type, 0, slash) &&
         is_base_name(type, slash + 1, type.size());
}

bool is_md5sum(const std::string &md5) {
  if (md5.size() != 32) return false;
  for (char c : md5) {
    if (!is_digit(c) && !((c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F'))) return false;
  }
  return true;
}

bool decode_topic_announcement(const std::vector<uint8_t> &payload, TopicAnnouncement *out,
                               std::string *why) {
  rosserial_msgs_TopicInfo info;
  std::size_t used = 0;
  if (!rosserial_msgs_TopicInfo_deserialize(&info, payload.data(), payload.size(), &used) ||
      used != payload.size()) {
    *why = "not a rosserial_msgs/TopicInfo";
    return false;
  }
  TopicAnnouncement a;
  a.topic_id = info.topic_id;
  a.name = to_string(info.topic_name);
  a.type = to_string(info.message_type);
  a.md5 = to_string(info.md5sum);
  a.buffer_size = info.buffer_size;
  // The reserved ids are dispatched before any device topic, so such a topic could never carry
  // data; saying so beats silently never publishing it.
  if (a.topic_id < kFirstUserTopicId) {
    *why = "topic id " + std::to_string(a.topic_id) + " is reserved by rosserial";
  } else if (a.name.empty()) {
    *why = "empty topic name";
  } else if (!is_message_type(a.type)) {
    *why = "message type is not package/Message";
  } else if (!is_md5sum(a.md5)) {
    *why = "md5sum is not 32 hex digits";
  } else {
    *out = a;
    return true;
  }
  return false;
}

bool decode_device_log(const std::vector<uint8_t> &payload, DeviceLog *out) {
  rosserial_msgs_Log log;
  std::size_t used = 0;
  if (!rosserial_msgs_Log_deserialize(&log, payload.data(), payload.size(), &used) ||
      used != payload.size()) {
    return false;
  }
  out->level = log.level;
  out->text = to_string(log.msg);
  return true;
}

bool decode_param_request(const std::vector<uint8_t> &payload, std::string *name) {
  rosserial_msgs_RequestParamRequest req;
  std::size_t used = 0;
  if (!rosserial_msgs_RequestParamRequest_deserialize(&req, payload.data(), payload.size(),
                                                      &used) ||
      used != payload.size()) {
    return false;
  }
  *name = to_string(req.name);
  return true;
}

std::size_t max_param_values_per_type() { return HA_MSGS_VAR_ARRAY_CAP; }

bool encode_param_reply(const ParamValues &values, std::size_t max_payload,
                        std::vector<uint8_t> *payload, std::string *why) {
  const std::size_t cap = max_param_values_per_type();
  if (values.ints.size() > cap || values.floats.size() > cap || values.strings.size() > cap) {
    *why = "more than " + std::to_string(cap) + " values of one type";
    return false;
  }
  rosserial_msgs_RequestParamResponse resp{};
  for (int32_t v : values.ints) resp.ints[resp.ints_count++] = v;
  for (float v : values.floats) resp.floats[resp.floats_count++] = v;
  for (const std::string &s : values.strings) {
    if (s.size() > max_payload) {  // also keeps the length within the wire's uint32
      *why = "a string longer than the largest frame";
      return false;
    }
    resp.strings[resp.strings_count++] = HaRosString{s.data(), static_cast<uint32_t>(s.size())};
  }
  payload->assign(max_payload, 0);
  std::size_t n = 0;
  if (!rosserial_msgs_RequestParamResponse_serialize(&resp, payload->data(), payload->size(), &n)) {
    payload->clear();
    *why = "larger than the largest frame (" + std::to_string(max_payload) + " bytes)";
    return false;
  }
  payload->resize(n);
  return true;
}

}  // namespace arduino_link
