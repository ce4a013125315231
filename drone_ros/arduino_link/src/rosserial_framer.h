// Host side of rosserial protocol version 2 framing, free of ROS so it can be fuzzed and tested
// alone: bytes in (with the time they arrived), complete frames out, every kind of bad input
// counted and dropped. When a frame fails (protocol, length checksum, length, checksum), the
// search for a sync byte resumes one byte after the failed frame's sync byte, among the bytes it
// had taken (at most max_payload + 7), not at the next unread byte as rosserial_python does: a
// frame that lost a byte takes the next frame's sync byte as its checksum, and that next frame
// still arrives. Mirrors
// the device decoder (arduino_ha/src/link/ha_link_frame.c) but is written independently, so the
// two check each other in the pty tests.
#ifndef ARDUINO_LINK_ROSSERIAL_FRAMER_H
#define ARDUINO_LINK_ROSSERIAL_FRAMER_H

#include <cstddef>
#include <cstdint>
#include <vector>

namespace arduino_link {

struct Frame {
  uint16_t topic_id = 0;
  std::vector<uint8_t> payload;
};

struct FramerCounters {
  uint64_t frames_ok = 0;
  // Garbage where a sync byte was due, and the bytes of a failed frame passed over in the search
  // for the next sync byte (a failed frame's own sync byte is in its failure's count instead).
  uint64_t bytes_skipped = 0;
  uint64_t bad_protocol = 0;  // another protocol version (rosserial v1 sends 0xFF)
  uint64_t bad_length_checksum = 0;
  uint64_t oversized = 0;     // announced length above the limit
  uint64_t bad_checksum = 0;  // bit flips in topic or payload
  uint64_t timeouts = 0;      // frame stopped arriving mid-way
  uint64_t dropped() const {
    return bad_protocol + bad_length_checksum + oversized + bad_checksum + timeouts;
  }
};

class RosserialFramer {
 public:
  // max_payload: larger announced lengths are corruption; frame_timeout_s: how long a started
  // frame may take before it is dropped.
  RosserialFramer(std::size_t max_payload, double frame_timeout_s);

  // Appends every frame completed by these bytes to *out, in order. The frames may include some
  // whose bytes came in earlier calls (found inside a frame that failed only now), so a call can
  // complete several frames even with one byte.
  void feed(const uint8_t *data, std::size_t len, double now_s, std::vector<Frame> *out);
  // Drops a partial frame older than the timeout, with every byte it holds: they are stale.
  void poll(double now_s);
  // Forgets a partial frame (the port was reopened); counters are kept.
  void reset();

  const FramerCounters &counters() const { return counters_; }
  // Bytes of the partial frame, from its sync byte on, kept for parsing (and searching again).
  // Until a timeout, every byte fed is in a delivered frame (payload + 8), skipped, the sync byte
  // of one counted failure, or held.
  std::size_t bytes_held() const { return held_.size() - start_; }

 private:
  enum class State {
    kSync,
    kProtocol,
    kLenLo,
    kLenHi,
    kLenChecksum,
    kTopicLo,
    kTopicHi,
    kPayload,
    kChecksum
  };
  enum class Step { kMore, kSkipped, kFailed, kFrame };
  Step step(uint8_t byte, double now_s);
  void drop_held();

  std::size_t max_payload_;
  double frame_timeout_s_;
  State state_ = State::kSync;
  uint16_t length_ = 0;
  uint16_t topic_ = 0;
  unsigned sum_ = 0;
  double started_s_ = 0.0;
  std::vector<uint8_t> payload_;
  // held_[start_] is the sync byte of the frame being parsed (or, in kSync, the next byte to
  // look at); held_[start_, next_) have been parsed. Bytes before start_ are done with.
  std::vector<uint8_t> held_;
  std::size_t start_ = 0;
  std::size_t next_ = 0;
  FramerCounters counters_;
};

// The frame for one message: sync, protocol v2, length and its checksum, topic, payload, checksum.
std::vector<uint8_t> encode_frame(uint16_t topic_id, const uint8_t *payload, std::size_t len);

// The host's documented topic request: ff fe 00 00 ff 00 00 ff.
std::vector<uint8_t> topic_request_frame();
// The host's documented goodbye (ID_TX_STOP): ff fe 00 00 ff 0b 00 f4.
std::vector<uint8_t> tx_stop_frame();

}  // namespace arduino_link

#endif
