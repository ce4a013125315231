// libFuzzer harness for what the host makes of the reserved topics' payloads (TopicInfo
// announcements, logs, parameter requests) and of the parameter replies it builds. The same
// bytes go to every decoder, as a corrupted or hostile device could put them on any topic id.
// Whatever a decoder accepts must satisfy what the node relies on before handing it to ROS
// (user topic id, non-empty name, package/Message type, 32-hex md5sum) and must serialize back
// to exactly the input; a reply built from the bytes must read back equal and fit the limit.
// Nothing may crash, leak or hit UB (ASan + UBSan).
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "device_payloads.h"
#include "ha_link_msgs.h"

namespace {

using Bytes = std::vector<uint8_t>;

void check_announcement(const Bytes &in) {
  arduino_link::TopicAnnouncement a;
  std::string why;
  if (!arduino_link::decode_topic_announcement(in, &a, &why)) {
    if (why.empty()) std::abort();  // a refusal always says why: it goes into the warning
    return;
  }
  if (a.topic_id < arduino_link::kFirstUserTopicId || a.name.empty() ||
      !arduino_link::is_message_type(a.type) || !arduino_link::is_md5sum(a.md5)) {
    std::abort();
  }
  rosserial_msgs_TopicInfo info{};
  info.topic_id = a.topic_id;
  info.topic_name = HaRosString{a.name.data(), static_cast<uint32_t>(a.name.size())};
  info.message_type = HaRosString{a.type.data(), static_cast<uint32_t>(a.type.size())};
  info.md5sum = HaRosString{a.md5.data(), static_cast<uint32_t>(a.md5.size())};
  info.buffer_size = a.buffer_size;
  Bytes out(in.size());
  std::size_t n = 0;
  if (!rosserial_msgs_TopicInfo_serialize(&info, out.data(), out.size(), &n) || n != in.size() ||
      out != in) {
    std::abort();
  }
}

void check_log(const Bytes &in) {
  arduino_link::DeviceLog log;
  if (!arduino_link::decode_device_log(in, &log)) return;
  rosserial_msgs_Log msg{};
  msg.level = log.level;
  msg.msg = HaRosString{log.text.data(), static_cast<uint32_t>(log.text.size())};
  Bytes out(in.size());
  std::size_t n = 0;
  if (!rosserial_msgs_Log_serialize(&msg, out.data(), out.size(), &n) || n != in.size() ||
      out != in)
    std::abort();
}

void check_param_request(const Bytes &in) {
  std::string name;
  if (!arduino_link::decode_param_request(in, &name)) return;
  if (name.size() + 4 != in.size() || std::memcmp(name.data(), in.data() + 4, name.size()) != 0)
    std::abort();
}

// Values taken from the bytes: counts (possibly over the limit), numbers, strings of any length.
void check_param_reply(const Bytes &in) {
  if (in.size() < 4) return;
  arduino_link::ParamValues v;
  std::size_t pos = 4;
  for (unsigned k = 0; k < (in[0] % 12u) && pos + 4 <= in.size(); ++k, pos += 4) {
    int32_t i;
    std::memcpy(&i, in.data() + pos, 4);
    v.ints.push_back(i);
  }
  for (unsigned k = 0; k < (in[1] % 12u) && pos + 4 <= in.size(); ++k, pos += 4) {
    float f;
    std::memcpy(&f, in.data() + pos, 4);
    v.floats.push_back(f);
  }
  for (unsigned k = 0; k < (in[2] % 12u) && pos < in.size(); ++k) {
    const std::size_t len = in[pos] < in.size() - pos ? in[pos] : in.size() - pos;
    v.strings.emplace_back(reinterpret_cast<const char *>(in.data()) + pos, len);
    pos += len + 1;
  }
  const std::size_t max_payload = 64u + in[3] * 4u;
  Bytes payload;
  std::string why;
  if (!arduino_link::encode_param_reply(v, max_payload, &payload, &why)) {
    if (why.empty()) std::abort();
    return;
  }
  if (payload.size() > max_payload) std::abort();
  rosserial_msgs_RequestParamResponse back{};
  std::size_t used = 0;
  if (!rosserial_msgs_RequestParamResponse_deserialize(&back, payload.data(), payload.size(),
                                                       &used) ||
      used != payload.size() || back.ints_count != v.ints.size() ||
      back.floats_count != v.floats.size() || back.strings_count != v.strings.size()) {
    std::abort();
  }
  for (std::size_t k = 0; k < v.ints.size(); ++k) {
    if (back.ints[k] != v.ints[k]) std::abort();
  }
  for (std::size_t k = 0; k < v.floats.size(); ++k) {
    if (std::memcmp(&back.floats[k], &v.floats[k], 4) != 0) std::abort();  // bits, NaNs included
  }
  for (std::size_t k = 0; k < v.strings.size(); ++k) {
    if (std::string(back.strings[k].data, back.strings[k].len) != v.strings[k]) std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  const Bytes in(data, data + size);
  check_announcement(in);
  check_log(in);
  check_param_request(in);
  check_param_reply(in);
  return 0;
}
