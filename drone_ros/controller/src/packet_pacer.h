// Real time: when does the controller step? On the VN-200's packets, not on a free timer. A
// timer at any phase to the sensor held each packet up to a period before the GNC saw it, and the
// HA's period held the command up to another one (sensor to servo 12 ms at 100 Hz, issue 24).
//
// The rule, as hil/README.md ("Sensor to servo") writes it down:
// - A packet is complete once each of its five topics (/ins, /attitude, /gps_position,
//   /gps_velocity, /imu_PQR_acceleration) has brought its message: counts, not stamps, as
//   /attitude and /gps_velocity carry no header, and the five come over five connections in any
//   order.
// - Every packets_per_step-th complete packet runs a step on its arrival (the VN-200's rate is a
//   whole multiple of the controller's; the parameters refuse any other).
// - Never two steps closer than half a period: a late packet completed just after a fallback step
//   counts as taken by it, and the next packet steps, so the GNC's fixed dt is not stepped twice
//   in a millisecond.
// - A packet late or lost does not stop the HP: a step runs on the timer when none has run for
//   kFallbackPeriods periods, on whatever the board holds (its freshness checks mark a sensor
//   that stays silent). Below two periods, so the HA, which takes over after
//   late_periods_tolerated (1) periods in a row without a new command, never sees two in a row.
// No ROS calls: the node feeds it arrivals and its monotonic clock.
#ifndef CONTROLLER_PACKET_PACER_H
#define CONTROLLER_PACKET_PACER_H

#include <array>
#include <cstdint>

#include "lockstep_gate.h"

namespace controller {

class PacketPacer {
 public:
  static constexpr double kFallbackPeriods = 1.25;
  static constexpr double kMinGapPeriods = 0.5;

  PacketPacer(double period_s, uint32_t packets_per_step);
  // One message of a VN-200 topic (kInIns .. kInImu; others are ignored) arrived at now_s: true
  // when a step is due now. The caller steps and then calls stepped(now_s).
  bool on_sensor(LockstepInput input, double now_s);
  // A step ran at now_s, on a packet or on the fallback.
  void stepped(double now_s);
  // When a step must run without its packet.
  double fallback_at_s() const { return last_step_s_ + fallback_s_; }
  uint64_t complete_packets() const { return complete_; }

 private:
  double period_s_;
  double fallback_s_;
  uint32_t packets_per_step_;
  std::array<uint64_t, kInImu + 1> arrived_{};
  uint64_t complete_ = 0;  // packets whose five messages have all arrived
  uint64_t used_ = 0;      // of those, the ones a step has run on
  double last_step_s_ = -1e300;
};

}  // namespace controller

#endif
