// A raw 8N1 serial port over termios, shared by the nodes that talk to hardware on a serial line
// (the Due's USB serial for the `arduino` node, the VN-200's USB-serial adapter for `vn200`) and,
// in tests, by pseudo-terminals. Every failure is a return value, never an exception: a USB
// device that vanishes in flight is an ordinary event the node reports and recovers from.
#ifndef DRONE_ROS_COMMON_SERIAL_PORT_H
#define DRONE_ROS_COMMON_SERIAL_PORT_H

#include <cstddef>
#include <cstdint>
#include <string>

namespace drone_ros_common {

class SerialPort {
 public:
  SerialPort() = default;
  ~SerialPort();
  SerialPort(const SerialPort &) = delete;
  SerialPort &operator=(const SerialPort &) = delete;

  // Lowest and highest rate open() accepts. Rates with a termios constant (9600, 115200,
  // 921600, ...) are set through termios; any other rate in range (the VN-200's 128000, the
  // Due's 250000) through Linux termios2 (BOTHER), since no constant exists for it.
  static constexpr int kMinBaud = 1200;
  static constexpr int kMaxBaud = 4000000;
  static bool baud_supported(int baud);

  // Opens path raw (no echo, no line discipline, no flow control) at baud, dropping bytes that
  // arrived before. A symlink is followed on every open, so a re-plugged device is found again.
  // False with *error saying what failed and naming the path.
  bool open(const std::string &path, int baud, std::string *error);
  void close();
  bool is_open() const { return fd_ >= 0; }

  enum class ReadResult {
    kData,     // *got > 0 bytes are in buf
    kTimeout,  // nothing within timeout_ms (or interrupted): ask again
    kGone,     // hang-up, I/O error, or not open: close and reopen later
  };
  // Waits up to timeout_ms for bytes and reads at most cap of them; *got is how many.
  ReadResult read(uint8_t *buf, std::size_t cap, int timeout_ms, std::size_t *got);

  // Writes all len bytes, resuming after partial writes and interruptions, and waiting while
  // the driver's buffer is full. Gives up (false) when the port is gone or accepts nothing for
  // the write stall time (kWriteStallMs unless set): a device that stopped draining must not
  // hold the node up.
  static constexpr int kWriteStallMs = 100;
  bool write_all(const void *data, std::size_t len);
  void set_write_stall_ms(int ms) { write_stall_ms_ = ms; }

 private:
  int fd_ = -1;
  int write_stall_ms_ = kWriteStallMs;
};

}  // namespace drone_ros_common

#endif
