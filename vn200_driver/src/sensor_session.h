// One connection's conversation with the VN-200, independent of ROS and of the port: bytes in,
// decoded packets out through callbacks, configuration commands out through poll_command().
// Configuration: stop the ASCII async stream (register 6), then set Binary Output 1
// (register 75). Each write must come back as the sensor's echo; a $VNERR or silence means a
// resend, and after `max_attempts` the session reports Failed so the node can reconnect.
// Host time is passed in, so tests drive it without sleeping.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "vn_ascii.h"
#include "vn_binary.h"
#include "vn_command.h"
#include "vn_framer.h"

namespace vn200 {

class SensorSession {
 public:
  enum class State { Idle, Configuring, Configured, Failed };

  struct Options {
    VnBinaryOutputConfig output{};
    double response_timeout_s = 0.5;
    int max_attempts = 4;
  };

  struct Counters {
    uint64_t packets_decoded = 0;
    uint64_t binary_decode_errors = 0;  // framed with a valid CRC but not decodable
    uint64_t ascii_decode_errors = 0;
    uint64_t sensor_errors = 0;  // $VNERR received
    uint8_t last_sensor_error = 0;
    uint64_t config_resends = 0;
    uint64_t bytes = 0;
  };

  explicit SensorSession(const Options& options);

  // Starts (or restarts, after a reconnect) the configuration; clears the framer's buffer but
  // keeps every counter.
  void start(double now_s);
  // Feeds received bytes.
  void on_bytes(const uint8_t* data, size_t len, double now_s);
  // The command to send now, or "" when nothing is due.
  std::string poll_command(double now_s);

  State state() const { return state_; }
  const VnFramerStats& framer_stats() const { return framer_.stats; }
  const Counters& counters() const { return counters_; }
  uint64_t bad_packets() const;
  double last_byte_s() const { return last_byte_s_; }

  std::function<void(const VnBinaryData&, double now_s)> on_binary;
  std::function<void(const VnAsciiMsg&, double now_s)> on_ascii;

 private:
  void handle_ascii(const VnFrame& frame, double now_s);

  Options options_;
  VnFramer framer_{};
  State state_ = State::Idle;
  std::vector<std::string> steps_;
  std::vector<unsigned> step_regs_;
  size_t step_ = 0;
  int attempts_ = 0;
  bool awaiting_ = false;
  double sent_at_s_ = 0.0;
  double last_byte_s_ = -1.0;
  Counters counters_;
};

const char* sensor_error_text(uint8_t code);

}  // namespace vn200
