// A raw serial port over termios: the Due's USB serial (/dev/ttyACM*) or, in tests, a
// pseudo-terminal. Opening, reading with a timeout and writing whole buffers; errors are
// reported as return values so the node can treat "port gone" as an ordinary event.
#ifndef ARDUINO_LINK_SERIAL_PORT_H
#define ARDUINO_LINK_SERIAL_PORT_H

#include <cstddef>
#include <cstdint>
#include <string>

namespace arduino_link {

class SerialPort {
 public:
  SerialPort() = default;
  ~SerialPort();
  SerialPort(const SerialPort &) = delete;
  SerialPort &operator=(const SerialPort &) = delete;

  // True for 1200..4000000: standard rates through termios, others through termios2 (BOTHER).
  // The native USB port ignores the rate, but it must still be valid.
  static bool baud_supported(int baud);

  // Opens the path (a symlink is followed each time, so a re-plugged device is found again).
  bool open(const std::string &path, int baud, std::string *error);
  void close();
  bool is_open() const { return fd_ >= 0; }

  enum class ReadResult { kData, kTimeout, kGone };
  // Waits up to timeout_ms for bytes; *got is how many were read.
  ReadResult read(uint8_t *buf, std::size_t cap, int timeout_ms, std::size_t *got);
  // Writes everything or reports the port gone.
  bool write_all(const uint8_t *data, std::size_t len);

 private:
  int fd_ = -1;
};

}  // namespace arduino_link

#endif
