#include "serial_port.h"

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace vn200 {

namespace {

bool baudConstant(uint32_t baud, speed_t* out) {
  switch (baud) {
    case 9600: *out = B9600; return true;
    case 19200: *out = B19200; return true;
    case 38400: *out = B38400; return true;
    case 57600: *out = B57600; return true;
    case 115200: *out = B115200; return true;
    case 230400: *out = B230400; return true;
    case 460800: *out = B460800; return true;
    case 921600: *out = B921600; return true;
    default: return false;  // 128000 has no termios constant; not offered by the node
  }
}

}  // namespace

bool SerialPort::open(const std::string& path, uint32_t baud, std::string* error) {
  close();
  speed_t speed;
  if (!baudConstant(baud, &speed)) {
    *error = "unsupported baud " + std::to_string(baud);
    return false;
  }
  int fd = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    *error = path + ": " + std::strerror(errno);
    return false;
  }
  termios tio{};
  if (tcgetattr(fd, &tio) != 0) {
    *error = path + ": tcgetattr: " + std::strerror(errno);
    ::close(fd);
    return false;
  }
  cfmakeraw(&tio);
  tio.c_cflag |= CLOCAL | CREAD;
  tio.c_cflag &= ~static_cast<tcflag_t>(CSTOPB | CRTSCTS);
  tio.c_cc[VMIN] = 0;
  tio.c_cc[VTIME] = 0;
  if (cfsetispeed(&tio, speed) != 0 || cfsetospeed(&tio, speed) != 0 ||
      tcsetattr(fd, TCSANOW, &tio) != 0) {
    *error = path + ": tcsetattr: " + std::strerror(errno);
    ::close(fd);
    return false;
  }
  tcflush(fd, TCIOFLUSH);  // stale bytes from before the (re)connect would only be garbage
  fd_ = fd;
  return true;
}

void SerialPort::close() {
  if (fd_ >= 0) {
    ::close(fd_);
    fd_ = -1;
  }
}

long SerialPort::read(uint8_t* buf, size_t cap, int timeout_ms) {
  if (fd_ < 0) return -1;
  pollfd p{fd_, POLLIN, 0};
  int r = ::poll(&p, 1, timeout_ms);
  if (r < 0) return errno == EINTR ? 0 : -1;
  if (r == 0) return 0;
  if (p.revents & POLLIN) {
    ssize_t n = ::read(fd_, buf, cap);
    if (n > 0) return static_cast<long>(n);
    if (n < 0 && (errno == EAGAIN || errno == EINTR)) return 0;
    return -1;  // EOF or EIO: the device went away
  }
  if (p.revents & (POLLHUP | POLLERR | POLLNVAL)) return -1;
  return 0;
}

bool SerialPort::write(const void* data, size_t len) {
  const uint8_t* p = static_cast<const uint8_t*>(data);
  int stalls = 0;
  while (len > 0 && fd_ >= 0) {
    ssize_t n = ::write(fd_, p, len);
    if (n > 0) {
      p += n;
      len -= static_cast<size_t>(n);
      continue;
    }
    if (n < 0 && (errno == EAGAIN || errno == EINTR) && stalls < 20) {
      ++stalls;
      pollfd pf{fd_, POLLOUT, 0};
      ::poll(&pf, 1, 10);
      continue;
    }
    return false;
  }
  return len == 0;
}

}  // namespace vn200
