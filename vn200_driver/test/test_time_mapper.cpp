// Sensor clock to host clock: delay jitter must not reach the timestamps.
#include <gtest/gtest.h>

#include <cmath>

#include "time_mapper.h"

namespace {

TEST(TimeMapper, JitteryArrivalsGiveEvenlySpacedStamps) {
  vn200::TimeMapper m;
  const double offset = 1000.0;
  double worst = 0;
  for (int i = 0; i < 2000; ++i) {
    double sensor = i * 0.01;
    // 2 ms base latency plus up to 8 ms of USB/scheduler jitter, deterministic pattern.
    double delay = 0.002 + 0.008 * std::fabs(std::sin(i * 1.7));
    double stamp = m.map(sensor, sensor + offset + delay);
    if (i > 100) worst = std::max(worst, std::fabs(stamp - (sensor + offset + 0.002)));
  }
  EXPECT_LT(worst, 0.0015);  // within 1.5 ms of the least-delayed path, vs 8 ms raw jitter
}

TEST(TimeMapper, FollowsSlowClockDrift) {
  vn200::TimeMapper m;
  double stamp = 0;
  double sensor = 0;
  for (int i = 0; i < 20000; ++i) {
    sensor = i * 0.01;
    double host = sensor * (1.0 + 50e-6) + 5.0 + 0.001;  // 50 ppm fast host clock
    stamp = m.map(sensor, host);
  }
  EXPECT_NEAR(sensor * (1.0 + 50e-6) + 5.0 + 0.001, stamp, 0.001);
}

TEST(TimeMapper, SensorRestartResetsTheOffset) {
  vn200::TimeMapper m;
  for (int i = 0; i < 100; ++i) m.map(500.0 + i * 0.01, 1000.0 + i * 0.01);
  // The sensor rebooted: its startup clock went back to zero.
  double stamp = m.map(0.0, 1001.5);
  EXPECT_NEAR(1001.5, stamp, 1e-9);
  EXPECT_EQ(1u, m.resets());
}

}  // namespace
