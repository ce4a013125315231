// Maps the sensor's clock to host time. A packet's arrival time = sensor time + clock offset +
// a transport delay that is never negative and only sometimes small (USB batching, scheduler).
// So the offset estimate follows the smallest recent (host - sensor) sample at once and creeps up
// slowly otherwise, which tracks clock drift without inheriting the delay jitter. A jump larger
// than `reset_threshold_s` (sensor restart, time source switch) restarts the estimate.
#pragma once

namespace vn200 {

class TimeMapper {
 public:
  explicit TimeMapper(double rise_gain = 0.01, double reset_threshold_s = 0.5)
      : rise_gain_(rise_gain), reset_threshold_s_(reset_threshold_s) {}
  // Host time [s] of the sample the sensor stamped `sensor_s`, seen at host time `arrival_s`.
  double map(double sensor_s, double arrival_s);
  void reset() { initialised_ = false; }
  bool initialised() const { return initialised_; }
  double offset_s() const { return offset_s_; }
  unsigned resets() const { return resets_; }

 private:
  double rise_gain_;
  double reset_threshold_s_;
  bool initialised_ = false;
  double offset_s_ = 0.0;
  double last_sensor_s_ = 0.0;
  unsigned resets_ = 0;
};

}  // namespace vn200
