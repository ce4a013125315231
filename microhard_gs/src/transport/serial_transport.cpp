#include "serial_transport.h"

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace microhard_gs {
namespace {
speed_t to_speed(int baud) {
  switch (baud) {
    case 9600: return B9600;
    case 19200: return B19200;
    case 38400: return B38400;
    case 57600: return B57600;
    case 115200: return B115200;
    case 230400: return B230400;
    case 460800: return B460800;
    case 921600: return B921600;
    default: return B0;
  }
}
}  // namespace

bool SerialTransport::is_supported_baud(int baud) { return to_speed(baud) != B0; }

std::unique_ptr<SerialTransport> SerialTransport::open(const std::string& port, int baud, std::string* error) {
  const speed_t speed = to_speed(baud);
  if (speed == B0) {
    *error = "unsupported baud " + std::to_string(baud);
    return nullptr;
  }
  const int fd = ::open(port.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    *error = "open " + port + ": " + std::strerror(errno);
    return nullptr;
  }
  termios tio;
  if (tcgetattr(fd, &tio) != 0) {
    *error = "tcgetattr " + port + ": " + std::strerror(errno);
    ::close(fd);
    return nullptr;
  }
  cfmakeraw(&tio);
  tio.c_cflag |= CLOCAL | CREAD;
  tio.c_cflag &= ~(CRTSCTS | CSTOPB);
  tio.c_cc[VMIN] = 0;
  tio.c_cc[VTIME] = 0;
  cfsetispeed(&tio, speed);
  cfsetospeed(&tio, speed);
  if (tcsetattr(fd, TCSANOW, &tio) != 0) {
    *error = "tcsetattr " + port + ": " + std::strerror(errno);
    ::close(fd);
    return nullptr;
  }
  return std::unique_ptr<SerialTransport>(new SerialTransport(fd, port, baud));
}

SerialTransport::~SerialTransport() { ::close(fd_); }

long SerialTransport::receive(uint8_t* buf, size_t cap) {
  const ssize_t n = ::read(fd_, buf, cap);
  if (n < 0) return (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) ? 0 : -1;
  return n;
}

bool SerialTransport::send(const uint8_t* data, size_t len) {
  size_t done = 0;
  int stalls = 0;
  while (done < len) {
    const ssize_t n = ::write(fd_, data + done, len - done);
    if (n > 0) {
      done += static_cast<size_t>(n);
      continue;
    }
    if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) return false;
    // The modem's buffer is full: wait a little, but never block the node for long.
    pollfd p{fd_, POLLOUT, 0};
    if (++stalls > 5 || poll(&p, 1, 10) < 0) return false;
  }
  return true;
}

std::string SerialTransport::describe() const { return "serial " + port_ + " @" + std::to_string(baud_); }

}  // namespace microhard_gs
