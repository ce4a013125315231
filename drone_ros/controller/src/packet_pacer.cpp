#include "packet_pacer.h"

#include <algorithm>

namespace controller {

PacketPacer::PacketPacer(double period_s, uint32_t packets_per_step)
    : period_s_(period_s),
      fallback_s_(kFallbackPeriods * period_s),
      packets_per_step_(std::max<uint32_t>(packets_per_step, 1u)) {}

bool PacketPacer::on_sensor(LockstepInput input, double now_s) {
  if (input > kInImu) {
    return false;
  }
  ++arrived_[input];
  const uint64_t complete = *std::min_element(arrived_.begin(), arrived_.end());
  if (complete == complete_) {
    return false;  // this message completed no packet
  }
  complete_ = complete;
  if (complete_ - used_ < packets_per_step_) {
    return false;
  }
  if (now_s - last_step_s_ < kMinGapPeriods * period_s_) {
    // A late packet just after a fallback step: that step had what the board held of it.
    used_ = complete_;
    return false;
  }
  return true;
}

void PacketPacer::stepped(double now_s) {
  // What arrived before this step is in it: a fallback step takes a packet still incomplete too,
  // and the packets counted so far are not waited for again.
  used_ = complete_;
  last_step_s_ = now_s;
}

}  // namespace controller
