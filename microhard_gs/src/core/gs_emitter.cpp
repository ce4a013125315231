#include "gs_emitter.h"

#include <algorithm>
#include <cstring>
#include <utility>

namespace microhard_gs {

void Emitter::statustext(uint8_t severity, const std::string& text) {
  // MAVLink 2 splits long texts into 50-character chunks sharing a non-zero id; the last chunk
  // is shorter than 50 (so it carries the terminator), hence the "<=" below.
  const size_t kChunk = MAVLINK_MSG_STATUSTEXT_FIELD_TEXT_LEN;
  const bool multi = text.size() >= kChunk;
  uint16_t id = 0;
  if (multi) {
    ++statustext_id_;
    if (statustext_id_ == 0) statustext_id_ = 1;
    id = statustext_id_;
  }
  for (size_t off = 0, seq = 0; off <= text.size() && seq < 8; off += kChunk, ++seq) {
    mavlink_statustext_t s{};
    s.severity = severity;
    const size_t n = std::min(kChunk, text.size() - off);
    std::memcpy(s.text, text.data() + off, n);
    s.id = id;
    s.chunk_seq = static_cast<uint8_t>(seq);
    emit([&](mavlink_message_t* m) {
      mavlink_msg_statustext_encode_status(system_id_, component_id_, &status_, m, &s);
    });
    if (!multi) break;
  }
}

std::vector<std::vector<uint8_t>> Emitter::take_frames() {
  std::vector<std::vector<uint8_t>> out;
  out.swap(frames_);
  return out;
}

}  // namespace microhard_gs
