#pragma once

#include <netinet/in.h>

#include <memory>
#include <string>

#include "transport.h"

namespace microhard_gs {

struct UdpConfig {
  std::string bind_address;  // local address to listen on
  int bind_port = 0;
  std::string remote_address;  // where telemetry goes until a GCS speaks to us
  int remote_port = 0;
  bool follow_sender = true;  // answer whichever address last sent us a datagram
};

class UdpTransport : public Transport {
 public:
  // nullptr and `error` set when the socket cannot be opened or bound.
  static std::unique_ptr<UdpTransport> open(const UdpConfig& config, std::string* error);
  ~UdpTransport() override;
  long receive(uint8_t* buf, size_t cap, int timeout_ms) override;
  bool send(const uint8_t* data, size_t len) override;
  std::string describe() const override;

 private:
  UdpTransport(int fd, const UdpConfig& config, const sockaddr_in& remote);
  int fd_;
  UdpConfig config_;
  sockaddr_in remote_;
};

}  // namespace microhard_gs
