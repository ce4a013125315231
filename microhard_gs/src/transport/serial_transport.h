#pragma once

#include <memory>
#include <string>

#include "transport.h"

namespace microhard_gs {

class SerialTransport : public Transport {
 public:
  // Opens the Microhard modem's port raw (8N1, no flow control) at `baud`.
  static std::unique_ptr<SerialTransport> open(const std::string& port, int baud, std::string* error);
  static bool is_supported_baud(int baud);
  ~SerialTransport() override;
  int fd() const override { return fd_; }
  long receive(uint8_t* buf, size_t cap) override;
  bool send(const uint8_t* data, size_t len) override;
  std::string describe() const override;

 private:
  SerialTransport(int fd, const std::string& port, int baud) : fd_(fd), port_(port), baud_(baud) {}
  int fd_;
  std::string port_;
  int baud_;
};

}  // namespace microhard_gs
