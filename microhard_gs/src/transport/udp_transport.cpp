#include "udp_transport.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace microhard_gs {
namespace {
bool make_address(const std::string& address, int port, sockaddr_in* out) {
  if (port < 0 || port > 65535) return false;
  std::memset(out, 0, sizeof *out);
  out->sin_family = AF_INET;
  out->sin_port = htons(static_cast<uint16_t>(port));
  return inet_pton(AF_INET, address.c_str(), &out->sin_addr) == 1;
}
}  // namespace

std::unique_ptr<UdpTransport> UdpTransport::open(const UdpConfig& config, std::string* error) {
  sockaddr_in local;
  sockaddr_in remote;
  if (!make_address(config.bind_address, config.bind_port, &local)) {
    *error = "bad UDP bind address " + config.bind_address + ":" + std::to_string(config.bind_port);
    return nullptr;
  }
  if (!make_address(config.remote_address, config.remote_port, &remote)) {
    *error = "bad UDP remote address " + config.remote_address + ":" +
             std::to_string(config.remote_port);
    return nullptr;
  }
  const int fd = socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd < 0) {
    *error = std::string("socket: ") + std::strerror(errno);
    return nullptr;
  }
  if (bind(fd, reinterpret_cast<const sockaddr*>(&local), sizeof local) != 0) {
    *error = "bind " + config.bind_address + ":" + std::to_string(config.bind_port) + ": " +
             std::strerror(errno);
    close(fd);
    return nullptr;
  }
  return std::unique_ptr<UdpTransport>(new UdpTransport(fd, config, remote));
}

UdpTransport::UdpTransport(int fd, const UdpConfig& config, const sockaddr_in& remote)
    : fd_(fd), config_(config), remote_(remote) {}

UdpTransport::~UdpTransport() { close(fd_); }

long UdpTransport::receive(uint8_t* buf, size_t cap, int timeout_ms) {
  pollfd p{fd_, POLLIN, 0};
  if (poll(&p, 1, timeout_ms) <= 0) return 0;  // nothing yet, or a signal: ask again next loop
  sockaddr_in from;
  socklen_t from_len = sizeof from;
  const ssize_t n = recvfrom(fd_, buf, cap, 0, reinterpret_cast<sockaddr*>(&from), &from_len);
  if (n < 0) return (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) ? 0 : -1;
  if (config_.follow_sender && from_len == sizeof from && from.sin_family == AF_INET)
    remote_ = from;
  return n;
}

bool UdpTransport::send(const uint8_t* data, size_t len) {
  const ssize_t n =
      sendto(fd_, data, len, 0, reinterpret_cast<const sockaddr*>(&remote_), sizeof remote_);
  return n == static_cast<ssize_t>(len);
}

std::string UdpTransport::describe() const {
  char addr[INET_ADDRSTRLEN] = "?";
  inet_ntop(AF_INET, &remote_.sin_addr, addr, sizeof addr);
  return "udp " + config_.bind_address + ":" + std::to_string(config_.bind_port) + " -> " + addr +
         ":" + std::to_string(ntohs(remote_.sin_port));
}

}  // namespace microhard_gs
