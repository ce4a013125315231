// The binary output the node asks the VN-200 for, in one place so the node, the tests, the
// benchmark and the fake sensor agree on it.
#pragma once

#include <cstddef>
#include <cstdint>

#include "vn_command.h"

namespace vn200 {

// Binary Output `output` (1..3: register 74 + output), routed to `port` only: Common (times,
// attitude, rates, INS position/velocity, acceleration, mag/temperature/pressure, INS status),
// GPS (satellites, fix, uncertainties), Attitude (YPR uncertainty), INS (position/velocity
// uncertainty).
VnBinaryOutputConfig node_output_config(unsigned rate_hz, VnAsyncMode port, unsigned output);

// Whether `rate_hz` is an output rate the sensor can produce (800 Hz / integer divisor).
bool rate_supported(unsigned rate_hz);

// Serial bytes per second the configured stream needs (10 bits per byte on the wire).
double stream_bits_per_second(const VnBinaryOutputConfig& cfg, unsigned rate_hz);

}  // namespace vn200
