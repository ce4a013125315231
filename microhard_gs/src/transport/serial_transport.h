// The Microhard modem's serial port, through the project's shared drone_ros_common::SerialPort
// (raw 8N1, tells a silent modem from an unplugged one). The modem is a USB device that can be
// missing at start-up or vanish in flight; neither is fatal: the link is then down, the node
// keeps running, and the port is reopened every reopen period until it is back.
#pragma once

#include <drone_ros_common/serial_port.h>

#include <string>

#include "transport.h"

namespace microhard_gs {

class SerialTransport : public Transport {
 public:
  // Nothing is opened here: the first maintain() tries, so a missing port is an outage, not an
  // error. `port` may be a symlink (udev's by-id name); it is followed on every open.
  SerialTransport(const std::string& port, int baud, uint64_t reopen_period_ms);
  static bool is_supported_baud(int baud) {
    return drone_ros_common::SerialPort::baud_supported(baud);
  }
  long receive(uint8_t* buf, size_t cap, int timeout_ms) override;
  bool send(const uint8_t* data, size_t len) override;
  void maintain(uint64_t now_ms) override;
  std::string describe() const override;

 private:
  drone_ros_common::SerialPort port_;
  std::string path_;
  int baud_;
  uint64_t reopen_period_ms_;
  bool tried_ = false;
  bool lost_ = false;  // receive() saw the port go; maintain() stamps the outage
  uint64_t last_attempt_ms_ = 0;
};

}  // namespace microhard_gs
