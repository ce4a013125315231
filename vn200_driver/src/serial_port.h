// A raw 8N1 serial port over termios (a USB-serial adapter or, in tests, a pseudo-terminal).
// Every failure is returned, never thrown: a vanished USB device is an expected event.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace vn200 {

class SerialPort {
 public:
  SerialPort() = default;
  ~SerialPort() { close(); }
  SerialPort(const SerialPort&) = delete;
  SerialPort& operator=(const SerialPort&) = delete;

  // Opens `path` at `baud` in raw mode; false with *error set on failure.
  bool open(const std::string& path, uint32_t baud, std::string* error);
  void close();
  bool isOpen() const { return fd_ >= 0; }
  // Waits up to timeout_ms for data. Returns bytes read (0 on timeout), or -1 when the device
  // is gone (hang-up, I/O error): the caller closes and reconnects.
  long read(uint8_t* buf, size_t cap, int timeout_ms);
  // Writes all of data (briefly waiting when the driver's buffer is full); false on failure.
  bool write(const void* data, size_t len);

 private:
  int fd_ = -1;
};

}  // namespace vn200
