#include "serial_port.h"

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "custom_baud.h"

namespace arduino_link {

namespace {
bool speed_of(int baud, speed_t *speed) {
  switch (baud) {
    case 9600: *speed = B9600; return true;
    case 19200: *speed = B19200; return true;
    case 38400: *speed = B38400; return true;
    case 57600: *speed = B57600; return true;
    case 115200: *speed = B115200; return true;
    case 230400: *speed = B230400; return true;
    case 460800: *speed = B460800; return true;
    case 500000: *speed = B500000; return true;
    case 921600: *speed = B921600; return true;
    case 1000000: *speed = B1000000; return true;
    default: return false;
  }
}
}  // namespace

SerialPort::~SerialPort() { close(); }

// Rates without a termios constant go through termios2; this range covers every USB-serial
// bridge and UART the Due is likely to meet.
constexpr int kMinCustomBaud = 1200;
constexpr int kMaxCustomBaud = 4000000;

bool SerialPort::baud_supported(int baud) { return baud >= kMinCustomBaud && baud <= kMaxCustomBaud; }

bool SerialPort::open(const std::string &path, int baud, std::string *error) {
  close();
  if (!baud_supported(baud)) {
    *error = "unsupported baud rate";
    return false;
  }
  speed_t speed = B115200;
  const bool standard = speed_of(baud, &speed);
  const int fd = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    *error = std::strerror(errno);
    return false;
  }
  termios tio{};
  if (tcgetattr(fd, &tio) != 0) {
    *error = std::strerror(errno);
    ::close(fd);
    return false;
  }
  cfmakeraw(&tio);  // binary protocol: no echo, no line discipline, no flow control
  tio.c_cflag |= CLOCAL | CREAD;
  tio.c_cflag &= ~static_cast<tcflag_t>(CRTSCTS);
  tio.c_cc[VMIN] = 0;
  tio.c_cc[VTIME] = 0;
  cfsetispeed(&tio, speed);
  cfsetospeed(&tio, speed);
  if (tcsetattr(fd, TCSANOW, &tio) != 0) {
    *error = std::strerror(errno);
    ::close(fd);
    return false;
  }
  if (!standard && !set_custom_baud(fd, baud)) {
    *error = "the driver refused " + std::to_string(baud) + " baud";
    ::close(fd);
    return false;
  }
  tcflush(fd, TCIOFLUSH);  // bytes from before we were listening belong to nobody
  fd_ = fd;
  return true;
}

void SerialPort::close() {
  if (fd_ >= 0) {
    ::close(fd_);
    fd_ = -1;
  }
}

SerialPort::ReadResult SerialPort::read(uint8_t *buf, std::size_t cap, int timeout_ms, std::size_t *got) {
  *got = 0;
  if (fd_ < 0) return ReadResult::kGone;
  pollfd pfd{fd_, POLLIN, 0};
  const int r = ::poll(&pfd, 1, timeout_ms);
  if (r < 0) return (errno == EINTR) ? ReadResult::kTimeout : ReadResult::kGone;
  if (r == 0) return ReadResult::kTimeout;
  if ((pfd.revents & POLLIN) != 0) {
    const ssize_t n = ::read(fd_, buf, cap);
    if (n > 0) {
      *got = static_cast<std::size_t>(n);
      return ReadResult::kData;
    }
    if (n < 0 && (errno == EAGAIN || errno == EINTR)) return ReadResult::kTimeout;
    return ReadResult::kGone;  // EOF or EIO: the USB device (or the pty's other end) went away
  }
  if ((pfd.revents & (POLLHUP | POLLERR | POLLNVAL)) != 0) return ReadResult::kGone;
  return ReadResult::kTimeout;
}

bool SerialPort::write_all(const uint8_t *data, std::size_t len) {
  std::size_t done = 0;
  int stalls = 0;
  while (done < len) {
    if (fd_ < 0) return false;
    const ssize_t n = ::write(fd_, data + done, len - done);
    if (n > 0) {
      done += static_cast<std::size_t>(n);
      continue;
    }
    if (n < 0 && (errno == EAGAIN || errno == EINTR)) {
      // The device is not draining: wait a little, but never block the node for long.
      pollfd pfd{fd_, POLLOUT, 0};
      if (::poll(&pfd, 1, 10) <= 0 && ++stalls > 10) return false;
      continue;
    }
    return false;
  }
  return true;
}

}  // namespace arduino_link
