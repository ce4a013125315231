// A byte link to the ground: UDP on the bench, the Microhard modem's serial port in the air.
// The node calls receive() as its loop's wait, so a link paces the loop whether it is up or not.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace microhard_gs {

// What the node reports about its link in the diagnostics.
struct LinkHealth {
  bool up = true;
  uint64_t opens = 0;          // successful opens, the first one included
  uint64_t outages = 0;        // times an open link went away (unplug, modem reset)
  uint64_t open_failures = 0;  // attempts that found no usable port
  uint64_t down_since_ms = 0;  // monotonic time the current outage began (when !up)
  std::string last_error;      // why the link is down, or went down last
};

class Transport {
 public:
  virtual ~Transport() = default;
  // Waits up to timeout_ms for bytes and reads what is there into buf; returns bytes read (0
  // when none came), -1 on a hard error. A link that is down just waits out the timeout.
  virtual long receive(uint8_t* buf, size_t cap, int timeout_ms) = 0;
  // Sends one MAVLink frame (one datagram on UDP). False when the link refused it or is down.
  virtual bool send(const uint8_t* data, size_t len) = 0;
  // Called every loop with the monotonic time: a link that can vanish reopens itself here.
  virtual void maintain(uint64_t now_ms) { (void)now_ms; }
  // Read every loop: a reference, not a copy. A link that never drops (UDP) leaves it as made.
  const LinkHealth& health() const { return health_; }
  virtual std::string describe() const = 0;

 protected:
  LinkHealth health_;
};

}  // namespace microhard_gs
