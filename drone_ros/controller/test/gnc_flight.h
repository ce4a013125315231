// The closed-loop harness the GNC tests share: the generated controller (through its C entry
// points, as the node calls it) stepped against the nonlinear 6-DOF model of test/sim, with the
// aircraft's own controller_param.yaml and limits.yaml.
#ifndef CONTROLLER_TEST_GNC_FLIGHT_H
#define CONTROLLER_TEST_GNC_FLIGHT_H

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <string>

#include "controller_params.h"
#include "sim/airframe_sim.h"
#include "yaml_lookup.h"

namespace controller_test {

constexpr double kPi = 3.14159265358979323846;
constexpr double kRadToDeg = 180.0 / kPi;

class Flight {
 public:
  explicit Flight(const std::map<std::string, double> &overrides = {},
                  const airframe_sim::SimConfig &sim_config = airframe_sim::SimConfig{})
      : sim_(sim_config) {
    values_ = controller_test::aircraft_params(AIRCRAFT_DIR, overrides);
    std::string error;
    ok_ =
        controller::build_controller_params(controller_test::lookup_in(values_), &params_, &error);
    EXPECT_TRUE(ok_) << error;
    EXPECT_EQ(gnc_initialize(&params_.gnc), 0);
    in_ = GncInput{};
    in_.piccic = 1;  // computer in command
    in_.throttle_trim = params_.throttle_trim;
    in_.elevator_trim_rad = params_.elevator_trim_rad;
    in_.aileron_trim_rad = params_.aileron_trim_rad;
    in_.rudder_trim_rad = params_.rudder_trim_rad;
  }
  ~Flight() { gnc_terminate(); }

  // In level flight at the design speed, height_ft above home, heading psi_rad.
  void start_trimmed(double height_ft, double psi_rad = 0.0) {
    sim_.set_trimmed_flight(params_.gnc.vt_trim_ftps, height_ft, psi_rad);
  }

  void set_plan(const double (*wps)[3], int count) {
    for (int i = 0; i < count; ++i) {
      in_.wp_north_ft[i] = wps[i][0];
      in_.wp_east_ft[i] = wps[i][1];
      in_.wp_height_ft[i] = wps[i][2];
      in_.wp_velocity_ftps[i] = params_.gnc.vt_trim_ftps;
    }
    in_.wp_count = count;
    ++in_.wp_revision;
  }

  void step() {
    sim_.sense(in_);
    gnc_step(&in_, &out_);
    sim_.advance(out_, params_.gnc.dt_s);
    t_s_ += params_.gnc.dt_s;
  }

  // Steps until the clock reads t_s.
  void fly_until(double t_s) {
    while (t_s_ < t_s) step();
  }

  double dt() const { return params_.gnc.dt_s; }
  void advance_clock() { t_s_ += params_.gnc.dt_s; }
  airframe_sim::Sim &sim() { return sim_; }
  GncInput &in() { return in_; }
  const GncOutput &out() const { return out_; }
  // For a caller that steps the GNC itself (a pilot or the HA flying the sim).
  void set_out(const GncOutput &out) { out_ = out; }
  const controller::ControllerParams &params() const { return params_; }
  double t() const { return t_s_; }
  // A value of controller_param.yaml or limits.yaml ("limits/actuators/aileron_limit_deg").
  double value(const std::string &key) const {
    const auto it = values_.find(key);
    EXPECT_NE(it, values_.end()) << key;
    return it == values_.end() ? std::numeric_limits<double>::quiet_NaN() : it->second;
  }

 private:
  std::map<std::string, double> values_;
  controller::ControllerParams params_{};
  bool ok_ = false;
  airframe_sim::Sim sim_;
  GncInput in_{};
  GncOutput out_{};
  double t_s_ = 0.0;
};

inline bool all_finite(const GncOutput &o) {
  const double v[] = {o.throttle,           o.elevator_rad,  o.aileron_rad,  o.rudder_rad,
                      o.vt_est_ftps,        o.alpha_est_rad, o.beta_est_rad, o.wind_north_ftps,
                      o.wind_east_ftps,     o.wind_up_ftps,  o.phi_cmd_rad,  o.theta_cmd_rad,
                      o.vt_cmd_ftps,        o.n_op_ft,       o.e_op_ft,      o.h_op_ft,
                      o.dist_to_waypoint_ft};
  return std::all_of(std::begin(v), std::end(v), [](double x) { return std::isfinite(x); });
}

}  // namespace controller_test

#endif
