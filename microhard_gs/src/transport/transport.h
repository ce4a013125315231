// A byte link to the ground: UDP on the bench, the Microhard modem's serial port in the air.
// Non-blocking; the node polls fd() and calls receive() when it is readable.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace microhard_gs {

class Transport {
 public:
  virtual ~Transport() = default;
  virtual int fd() const = 0;
  // Reads what is available into buf; returns bytes read (0 when nothing), -1 on a hard error.
  virtual long receive(uint8_t* buf, size_t cap) = 0;
  // Sends one MAVLink frame (one datagram on UDP). False when the link refused it.
  virtual bool send(const uint8_t* data, size_t len) = 0;
  virtual std::string describe() const = 0;
};

}  // namespace microhard_gs
