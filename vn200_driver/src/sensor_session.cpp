#include "sensor_session.h"

namespace vn200 {

SensorSession::SensorSession(const Options& options) : options_(options) {
  vn_framer_init(&framer_);
  char buf[VN_CMD_MAX];
  size_t n = vn_cmd_async_off(buf, sizeof buf, VN_CK_XOR8);
  steps_.emplace_back(buf, n);
  step_regs_.push_back(VN_REG_ASYNC_TYPE);
  n = vn_cmd_binary_output(buf, sizeof buf, &options_.output, VN_CK_XOR8);
  // An invalid output configuration is rejected by parameter validation before we get here;
  // if it slipped through, the empty step makes the session fail visibly instead of streaming
  // something nobody asked for.
  steps_.emplace_back(buf, n);
  step_regs_.push_back(VN_REG_BINARY_OUTPUT_1 - 1u + options_.output.output);
}

void SensorSession::start(double now_s) {
  // A fresh framer (bytes from before the reconnect are not a packet's start), but the counters
  // keep their totals: diagnostics report the node's whole run, not the last connection.
  const VnFramerStats totals = framer_.stats;
  vn_framer_init(&framer_);
  framer_.stats = totals;
  state_ = State::Configuring;
  step_ = 0;
  attempts_ = 0;
  awaiting_ = false;
  sent_at_s_ = now_s;
}

uint64_t SensorSession::bad_packets() const {
  return vn_framer_bad_packets(&framer_.stats) + counters_.binary_decode_errors +
         counters_.ascii_decode_errors;
}

std::string SensorSession::poll_command(double now_s) {
  if (state_ != State::Configuring) return "";
  if (awaiting_ && now_s - sent_at_s_ < options_.response_timeout_s) return "";
  if (awaiting_) ++counters_.config_resends;
  if (attempts_ >= options_.max_attempts || steps_[step_].empty()) {
    state_ = State::Failed;
    awaiting_ = false;
    return "";
  }
  ++attempts_;
  awaiting_ = true;
  sent_at_s_ = now_s;
  return steps_[step_];
}

void SensorSession::on_bytes(const uint8_t* data, size_t len, double now_s) {
  if (len > 0) last_byte_s_ = now_s;
  counters_.bytes += len;
  size_t off = 0;
  for (;;) {
    size_t used = 0;
    VnFrame frame;
    int got = vn_framer_next(&framer_, data + off, len - off, &used, &frame);
    off += used;
    if (!got) break;
    if (frame.kind == VN_FRAME_BINARY) {
      VnBinaryData d;
      if (vn_bin_decode(frame.data, frame.len, &d) == VN_BIN_OK) {
        ++counters_.packets_decoded;
        if (on_binary) on_binary(d, now_s);
      } else {
        ++counters_.binary_decode_errors;
      }
    } else {
      handle_ascii(frame, now_s);
    }
  }
}

void SensorSession::handle_ascii(const VnFrame& frame, double now_s) {
  VnAsciiMsg m;
  const char* s = reinterpret_cast<const char*>(frame.data);
  if (vn_ascii_parse(s, frame.len, &m) != VN_ASCII_OK) {
    ++counters_.ascii_decode_errors;
    return;
  }
  if (m.kind == VN_ASCII_ERROR) {
    ++counters_.sensor_errors;
    counters_.last_sensor_error = m.error_code;
    if (state_ == State::Configuring && awaiting_) {
      sent_at_s_ = now_s - options_.response_timeout_s;  // resend at the next poll
    }
    return;
  }
  if (state_ == State::Configuring && awaiting_ && m.kind == VN_ASCII_WRITE_REG &&
      m.reg_id == step_regs_[step_]) {
    awaiting_ = false;
    attempts_ = 0;
    ++step_;
    if (step_ == steps_.size()) state_ = State::Configured;
    return;
  }
  if (on_ascii) on_ascii(m, now_s);
}

const char* sensor_error_text(uint8_t code) {
  switch (code) {
    case VN_ERR_HARD_FAULT:
      return "hard fault";
    case VN_ERR_SERIAL_BUFFER_OVERFLOW:
      return "serial buffer overflow";
    case VN_ERR_INVALID_CHECKSUM:
      return "invalid checksum";
    case VN_ERR_INVALID_COMMAND:
      return "invalid command";
    case VN_ERR_NOT_ENOUGH_PARAMETERS:
      return "not enough parameters";
    case VN_ERR_TOO_MANY_PARAMETERS:
      return "too many parameters";
    case VN_ERR_INVALID_PARAMETER:
      return "invalid parameter";
    case VN_ERR_INVALID_REGISTER:
      return "invalid register";
    case VN_ERR_UNAUTHORIZED_ACCESS:
      return "unauthorized access";
    case VN_ERR_WATCHDOG_RESET:
      return "watchdog reset";
    case VN_ERR_OUTPUT_BUFFER_OVERFLOW:
      return "output buffer overflow";
    case VN_ERR_INSUFFICIENT_BAUD_RATE:
      return "insufficient baud rate";
    case VN_ERR_ERROR_BUFFER_OVERFLOW:
      return "error buffer overflow";
    default:
      return "none";
  }
}

}  // namespace vn200
