#include "rosserial_framer.h"

namespace arduino_link {

namespace {
constexpr uint8_t kSync = 0xFF;
constexpr uint8_t kProtocolV2 = 0xFE;
constexpr uint16_t kTopicIdPublisher = 0;
constexpr uint16_t kTopicIdTxStop = 11;

uint8_t checksum(unsigned sum) { return static_cast<uint8_t>(255u - (sum % 256u)); }
}  // namespace

RosserialFramer::RosserialFramer(std::size_t max_payload, double frame_timeout_s)
    : max_payload_(max_payload), frame_timeout_s_(frame_timeout_s) {
  payload_.reserve(max_payload_);
  held_.reserve(max_payload_ + 8);
}

void RosserialFramer::drop_held() {
  state_ = State::kSync;
  held_.clear();
  start_ = 0;
  next_ = 0;
}

void RosserialFramer::reset() { drop_held(); }

void RosserialFramer::poll(double now_s) {
  if (state_ != State::kSync && now_s - started_s_ > frame_timeout_s_) {
    ++counters_.timeouts;
    drop_held();
  }
}

void RosserialFramer::feed(const uint8_t *data, std::size_t len, double now_s,
                           std::vector<Frame> *out) {
  poll(now_s);
  held_.insert(held_.end(), data, data + len);
  while (next_ < held_.size()) {
    switch (step(held_[next_++], now_s)) {
      case Step::kMore:
        break;
      case Step::kSkipped:
        start_ = next_;
        break;
      case Step::kFrame: {
        Frame f;
        f.topic_id = topic_;
        f.payload = payload_;
        out->push_back(std::move(f));
        state_ = State::kSync;
        start_ = next_;
        break;
      }
      case Step::kFailed:
        // The bytes after the failed sync byte may hold the next frame's start: search them
        // again. Each failure moves start_ on by one, so this ends within the bytes held.
        state_ = State::kSync;
        ++start_;
        next_ = start_;
        break;
    }
  }
  // Only the partial frame (at most max_payload + 7 bytes) is kept across calls.
  held_.erase(held_.begin(), held_.begin() + static_cast<std::ptrdiff_t>(start_));
  next_ -= start_;
  start_ = 0;
}

RosserialFramer::Step RosserialFramer::step(uint8_t byte, double now_s) {
  switch (state_) {
    case State::kSync:
      if (byte != kSync) {
        ++counters_.bytes_skipped;
        return Step::kSkipped;
      }
      state_ = State::kProtocol;
      started_s_ = now_s;  // bytes found again are as late as the latest call
      break;
    case State::kProtocol:
      if (byte != kProtocolV2) {
        ++counters_.bad_protocol;  // v1, or a run of 0xFF: the search may start a frame at this one
        return Step::kFailed;
      }
      state_ = State::kLenLo;
      break;
    case State::kLenLo:
      length_ = byte;
      state_ = State::kLenHi;
      break;
    case State::kLenHi:
      length_ = static_cast<uint16_t>(length_ | (byte << 8));
      state_ = State::kLenChecksum;
      break;
    case State::kLenChecksum:
      if (((length_ & 0xFFu) + (length_ >> 8) + byte) % 256u != 255u) {
        ++counters_.bad_length_checksum;
        return Step::kFailed;
      }
      if (length_ > max_payload_) {
        ++counters_.oversized;
        return Step::kFailed;
      }
      state_ = State::kTopicLo;
      break;
    case State::kTopicLo:
      topic_ = byte;
      sum_ = byte;
      state_ = State::kTopicHi;
      break;
    case State::kTopicHi:
      topic_ = static_cast<uint16_t>(topic_ | (byte << 8));
      sum_ += byte;
      payload_.clear();
      state_ = (length_ == 0) ? State::kChecksum : State::kPayload;
      break;
    case State::kPayload:
      payload_.push_back(byte);
      sum_ += byte;
      if (payload_.size() >= length_) {
        state_ = State::kChecksum;
      }
      break;
    case State::kChecksum:
      if ((sum_ + byte) % 256u != 255u) {
        ++counters_.bad_checksum;
        return Step::kFailed;
      }
      ++counters_.frames_ok;
      return Step::kFrame;
  }
  return Step::kMore;
}

std::vector<uint8_t> encode_frame(uint16_t topic_id, const uint8_t *payload, std::size_t len) {
  std::vector<uint8_t> f;
  f.reserve(len + 8);
  const uint8_t len_lo = static_cast<uint8_t>(len & 0xFFu);
  const uint8_t len_hi = static_cast<uint8_t>((len >> 8) & 0xFFu);
  const uint8_t topic_lo = static_cast<uint8_t>(topic_id & 0xFFu);
  const uint8_t topic_hi = static_cast<uint8_t>(topic_id >> 8);
  f.push_back(kSync);
  f.push_back(kProtocolV2);
  f.push_back(len_lo);
  f.push_back(len_hi);
  f.push_back(checksum(len_lo + len_hi));
  f.push_back(topic_lo);
  f.push_back(topic_hi);
  unsigned sum = topic_lo + topic_hi;
  for (std::size_t i = 0; i < len; ++i) {
    f.push_back(payload[i]);
    sum += payload[i];
  }
  f.push_back(checksum(sum));
  return f;
}

std::vector<uint8_t> topic_request_frame() { return encode_frame(kTopicIdPublisher, nullptr, 0); }
std::vector<uint8_t> tx_stop_frame() { return encode_frame(kTopicIdTxStop, nullptr, 0); }

}  // namespace arduino_link
