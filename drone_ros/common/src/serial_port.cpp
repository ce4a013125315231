#include "drone_ros_common/serial_port.h"

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <string>

#include "custom_baud.h"

namespace drone_ros_common {

namespace {

// Rates <termios.h> has a constant for; tools that read the port's speed back through termios
// (cfgetospeed) see these as themselves, not as BOTHER.
bool standard_speed(int baud, speed_t *speed) {
  switch (baud) {
    case 1200:
      *speed = B1200;
      return true;
    case 2400:
      *speed = B2400;
      return true;
    case 4800:
      *speed = B4800;
      return true;
    case 9600:
      *speed = B9600;
      return true;
    case 19200:
      *speed = B19200;
      return true;
    case 38400:
      *speed = B38400;
      return true;
    case 57600:
      *speed = B57600;
      return true;
    case 115200:
      *speed = B115200;
      return true;
    case 230400:
      *speed = B230400;
      return true;
    case 460800:
      *speed = B460800;
      return true;
    case 500000:
      *speed = B500000;
      return true;
    case 921600:
      *speed = B921600;
      return true;
    case 1000000:
      *speed = B1000000;
      return true;
    case 2000000:
      *speed = B2000000;
      return true;
    case 4000000:
      *speed = B4000000;
      return true;
    default:
      return false;
  }
}

std::string describe(const std::string &path, const char *step, int err) {
  return path + ": " + step + ": " + std::strerror(err);
}

// What a person at the bench does about a port that will not open: the fix, not only the errno.
std::string fix_for(int err) {
  switch (err) {
    case ENOENT:
    case ENODEV:
    case ENXIO:
      return " (is the device plugged in? ls -l /dev/serial/by-id/ lists the USB serial devices by "
             "name: give that path, which survives re-plugging, as the port)";
    case EACCES:
    case EPERM:
      return " (this user may not open it: sudo usermod -aG dialout $USER, then log out and in "
             "again; ls -l shows the device's group)";
    case EBUSY:
      return " (another program holds it: fuser -v the path; ModemManager grabs new USB serial "
             "devices)";
    case ENOTTY:
    case EINVAL:
      return " (the path is not a serial device: check it; /dev/serial/by-id/ names the real ones)";
    default:
      return "";
  }
}

}  // namespace

SerialPort::~SerialPort() { close(); }

bool SerialPort::baud_supported(int baud) { return baud >= kMinBaud && baud <= kMaxBaud; }

bool SerialPort::open(const std::string &path, int baud, std::string *error) {
  close();
  if (!baud_supported(baud)) {
    *error = path + ": baud " + std::to_string(baud) + " is outside " + std::to_string(kMinBaud) +
             ".." + std::to_string(kMaxBaud);
    return false;
  }
  const int fd = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    const int err = errno;
    *error = describe(path, "open", err) + fix_for(err);
    return false;
  }
  termios tio{};
  if (tcgetattr(fd, &tio) != 0) {
    const int err = errno;
    *error = describe(path, "not a serial port (tcgetattr)", err) + fix_for(ENOTTY);
    ::close(fd);
    return false;
  }
  cfmakeraw(&tio);  // binary protocols: no echo, no line editing, 8 data bits, no parity
  tio.c_cflag |= CLOCAL | CREAD;
  tio.c_cflag &= ~static_cast<tcflag_t>(CSTOPB | CRTSCTS);  // 1 stop bit, no flow control
  tio.c_cc[VMIN] = 0;
  tio.c_cc[VTIME] = 0;
  speed_t speed = B115200;  // custom rates start here, then termios2 replaces it
  const bool standard = standard_speed(baud, &speed);
  if (cfsetispeed(&tio, speed) != 0 || cfsetospeed(&tio, speed) != 0 ||
      tcsetattr(fd, TCSANOW, &tio) != 0) {
    *error = describe(path, "tcsetattr", errno);
    ::close(fd);
    return false;
  }
  if (!standard && !set_custom_baud(fd, baud)) {
    const int err = errno;  // before anything below can overwrite it
    const std::string step = "the driver refused " + std::to_string(baud) + " baud";
    *error = describe(path, step.c_str(), err);
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

SerialPort::ReadResult SerialPort::read(uint8_t *buf, std::size_t cap, int timeout_ms,
                                        std::size_t *got) {
  *got = 0;
  if (fd_ < 0) return ReadResult::kGone;
  pollfd pfd{fd_, POLLIN, 0};
  const int r = ::poll(&pfd, 1, timeout_ms);
  if (r < 0) return errno == EINTR ? ReadResult::kTimeout : ReadResult::kGone;
  if (r == 0) return ReadResult::kTimeout;
  // Read even when a hang-up is flagged too: bytes that arrived before the unplug still count.
  if ((pfd.revents & POLLIN) != 0) {
    const ssize_t n = ::read(fd_, buf, cap);
    if (n > 0) {
      *got = static_cast<std::size_t>(n);
      return ReadResult::kData;
    }
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) {
      return ReadResult::kTimeout;
    }
    // 0 (end of file) or EIO/ENXIO: the USB device, or the pty's other end, went away.
    return ReadResult::kGone;
  }
  if ((pfd.revents & (POLLHUP | POLLERR | POLLNVAL)) != 0) return ReadResult::kGone;
  return ReadResult::kTimeout;
}

bool SerialPort::write_all(const void *data, std::size_t len) {
  const auto *p = static_cast<const uint8_t *>(data);
  // The stall is measured on the clock, not by counting polls: a signal ends a poll early, and
  // counted as a whole poll a burst of signals would give up on a device that is draining.
  using Clock = std::chrono::steady_clock;
  Clock::time_point last_progress = Clock::now();
  while (len > 0) {
    if (fd_ < 0) return false;
    const ssize_t n = ::write(fd_, p, len);
    if (n > 0) {  // possibly partial: carry on with the rest
      p += n;
      len -= static_cast<std::size_t>(n);
      last_progress = Clock::now();
      continue;
    }
    if (n < 0 && errno == EINTR) continue;  // a signal, not the device: just retry
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
      // The driver's buffer is full: wait for room, but not forever.
      const auto stalled_ms =
          std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - last_progress)
              .count();
      if (stalled_ms >= write_stall_ms_) return false;
      pollfd pfd{fd_, POLLOUT, 0};
      const int r = ::poll(&pfd, 1, static_cast<int>(write_stall_ms_ - stalled_ms));
      if (r > 0 && (pfd.revents & (POLLHUP | POLLERR | POLLNVAL)) != 0) return false;
      continue;
    }
    return false;  // EIO/ENXIO: the device is gone
  }
  return true;
}

}  // namespace drone_ros_common
