#include "time_mapper.h"

#include <cmath>

namespace vn200 {

double TimeMapper::map(double sensor_s, double arrival_s) {
  const double sample = arrival_s - sensor_s;
  const bool jumped = initialised_ && (std::fabs(sample - offset_s_) > reset_threshold_s_ ||
                                       sensor_s < last_sensor_s_);
  if (!initialised_ || jumped) {
    if (jumped) ++resets_;
    offset_s_ = sample;
    initialised_ = true;
  } else if (sample < offset_s_) {
    offset_s_ = sample;  // a less delayed packet: the true offset is at most this
  } else {
    offset_s_ += rise_gain_ * (sample - offset_s_);
  }
  last_sensor_s_ = sensor_s;
  return sensor_s + offset_s_;
}

}  // namespace vn200
