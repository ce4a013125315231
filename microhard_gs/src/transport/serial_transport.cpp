#include "serial_transport.h"

#include <poll.h>

namespace microhard_gs {

SerialTransport::SerialTransport(const std::string& port, int baud, uint64_t reopen_period_ms)
    : path_(port), baud_(baud), reopen_period_ms_(reopen_period_ms) {
  health_.up = false;
  health_.last_error = "not opened yet";
}

void SerialTransport::maintain(uint64_t now_ms) {
  if (lost_) {
    lost_ = false;
    health_.down_since_ms = now_ms;
    last_attempt_ms_ = now_ms;  // a device that just vanished is not back within the same loop
    return;
  }
  if (port_.is_open()) return;
  if (tried_ && now_ms - last_attempt_ms_ < reopen_period_ms_) return;
  if (!tried_) health_.down_since_ms = now_ms;
  tried_ = true;
  last_attempt_ms_ = now_ms;
  std::string error;
  if (!port_.open(path_, baud_, &error)) {
    ++health_.open_failures;
    health_.last_error = error;
    return;
  }
  ++health_.opens;
  health_.up = true;
}

long SerialTransport::receive(uint8_t* buf, size_t cap, int timeout_ms) {
  if (!port_.is_open()) {
    // Down: still wait, so the node's loop keeps its pace instead of spinning.
    if (timeout_ms > 0) poll(nullptr, 0, timeout_ms);
    return 0;
  }
  size_t got = 0;
  switch (port_.read(buf, cap, timeout_ms, &got)) {
    case drone_ros_common::SerialPort::ReadResult::kData:
      return static_cast<long>(got);
    case drone_ros_common::SerialPort::ReadResult::kTimeout:
      return 0;
    case drone_ros_common::SerialPort::ReadResult::kGone:
      break;
  }
  port_.close();
  health_.up = false;
  ++health_.outages;
  health_.last_error = path_ + ": port closed or device unplugged";
  lost_ = true;
  return 0;
}

bool SerialTransport::send(const uint8_t* data, size_t len) {
  // write_all gives up after SerialPort::kWriteStallMs without progress: a modem that stopped
  // draining costs one frame, never the node's loop. An unplug is noticed by receive().
  return port_.is_open() && port_.write_all(data, len);
}

std::string SerialTransport::describe() const {
  return "serial " + path_ + " @" + std::to_string(baud_);
}

}  // namespace microhard_gs
