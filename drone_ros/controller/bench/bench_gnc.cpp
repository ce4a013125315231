// GNC step time on this host: the GNC flying the closed-loop model around a square,
// each gnc_step timed alone. Prints `metric: value unit` lines.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "controller_params.h"
#include "sim/airframe_sim.h"
#include "yaml_lookup.h"

int main() {
  const auto values = controller_test::aircraft_params(AIRCRAFT_DIR);
  controller::ControllerParams params;
  std::string error;
  if (!controller::build_controller_params(controller_test::lookup_in(values), &params, &error)) {
    std::fprintf(stderr, "bad parameters: %s\n", error.c_str());
    return 1;
  }
  if (gnc_initialize(&params.gnc) != 0) {
    return 1;
  }
  airframe_sim::Sim sim{airframe_sim::SimConfig{}};
  sim.set_trimmed_flight(params.gnc.vt_trim_ftps, 200.0, 0.0);
  GncInput in{};
  GncOutput out{};
  in.piccic = 1;
  in.throttle_trim = params.throttle_trim;
  in.elevator_trim_rad = params.elevator_trim_rad;
  const double square[4][2] = {{1000.0, 0.0}, {1000.0, 2000.0}, {-1000.0, 2000.0}, {-1000.0, 0.0}};
  for (int i = 0; i < 4; ++i) {
    in.wp_north_ft[i] = square[i][0];
    in.wp_east_ft[i] = square[i][1];
    in.wp_height_ft[i] = 200.0;
    in.wp_velocity_ftps[i] = params.gnc.vt_trim_ftps;
  }
  in.wp_count = 4;
  in.wp_revision = 1;
  const int steps = 20000;
  std::vector<double> us;
  us.reserve(steps);
  for (int i = 0; i < steps; ++i) {
    sim.sense(in);
    const auto t0 = std::chrono::steady_clock::now();
    gnc_step(&in, &out);
    const auto t1 = std::chrono::steady_clock::now();
    us.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
    sim.advance(out, params.gnc.dt_s);
  }
  std::sort(us.begin(), us.end());
  std::printf("gnc_step_p50: %.2f us\n", us[us.size() / 2]);
  std::printf("gnc_step_p99: %.2f us\n", us[us.size() * 99 / 100]);
  std::printf("gnc_step_max: %.2f us\n", us.back());
  gnc_terminate();
  return 0;
}
