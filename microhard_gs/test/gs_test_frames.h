// Reading what GsCore sends, for its tests: its frames decoded by the generated MAVLink library
// (the parser a ground station runs), picked by message id, and STATUSTEXT joined into one string.
#ifndef MICROHARD_GS_TEST_GS_TEST_FRAMES_H
#define MICROHARD_GS_TEST_GS_TEST_FRAMES_H

#include <cstdint>
#include <string>
#include <vector>

#include "gs_core.h"

namespace microhard_gs {
namespace test {

inline std::vector<mavlink_message_t> decode_all(const std::vector<std::vector<uint8_t>>& frames) {
  std::vector<mavlink_message_t> out;
  mavlink_status_t status{};
  mavlink_message_t buffer{};
  for (const auto& f : frames) {
    for (uint8_t b : f) {
      mavlink_message_t msg;
      mavlink_status_t s;
      if (mavlink_frame_char_buffer(&buffer, &status, b, &msg, &s) == MAVLINK_FRAMING_OK) {
        out.push_back(msg);
      }
    }
  }
  return out;
}

inline std::vector<mavlink_message_t> of_type(const std::vector<mavlink_message_t>& msgs,
                                              uint32_t id) {
  std::vector<mavlink_message_t> out;
  for (const auto& m : msgs) {
    if (m.msgid == id) {
      out.push_back(m);
    }
  }
  return out;
}

inline std::string statustexts(const std::vector<mavlink_message_t>& msgs) {
  std::string joined;
  for (const auto& t : of_type(msgs, MAVLINK_MSG_ID_STATUSTEXT)) {
    char text[51] = {};
    mavlink_msg_statustext_get_text(&t, text);
    joined += text;
  }
  return joined;
}

}  // namespace test
}  // namespace microhard_gs

#endif  // MICROHARD_GS_TEST_GS_TEST_FRAMES_H
