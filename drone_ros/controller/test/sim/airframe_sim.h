// A small nonlinear 6-DOF model of the build's aircraft for closed-loop tests and benchmarks of
// the GNC without ROS. Same equations as drone_ros/gnc/design/airframe_model.py, same data (through
// the generated gnc_aircraft.h), plus wind and sensor noise. Flat earth, NED, SI inside.
#ifndef AIRFRAME_SIM_H
#define AIRFRAME_SIM_H

#include <Eigen/Dense>
#include <random>

#include "gnc.h"

namespace airframe_sim {

struct SimConfig {
  double home_lat_deg = 40.0;
  double home_lon_deg = -83.0;
  double home_alt_m = 250.0;
  Eigen::Vector3d wind_ned_mps = Eigen::Vector3d::Zero();
  double noise_scale = 1.0;  // 0 for noiseless sensors
  // Model error: the real aircraft is not the design model. 1.0 = as designed.
  double mass_scale = 1.0;
  double drag_scale = 1.0;
  double control_power_scale = 1.0;  // all surface effectiveness
  unsigned seed = 808;
};

class Sim {
 public:
  explicit Sim(const SimConfig &config);
  // Level trimmed flight at airspeed, height above home and heading (the design trim scaled).
  void set_trimmed_flight(double airspeed_ftps, double height_ft, double psi_rad);
  // At rest on the ground at home, wings level, weight on the wheels, nose to psi_rad. The
  // pitot reads the wind blowing over it.
  void set_on_ground(double psi_rad = 0.0);
  // From rest on the ground: the take-off roll along the nose at accel_mps2 (the wheels keep the
  // track on the nose, whatever the crosswind); at liftoff_ftps of airspeed the aircraft leaves
  // the ground level, weathervaned into the relative wind, and flies as the 6-DOF model.
  void start_takeoff_roll(double accel_mps2, double liftoff_ftps);
  bool on_ground() const { return on_ground_; }
  // Advance by dt_s holding the command (surfaces in rad, throttle 0..1).
  void advance(const GncOutput &cmd, double dt_s);
  // Fills the sensor part of a GNC input (trims, plan and PIC left to the caller).
  void sense(GncInput &in);

  double north_ft() const { return pos_ned_m_.x() / 0.3048; }
  double east_ft() const { return pos_ned_m_.y() / 0.3048; }
  double height_ft() const { return -pos_ned_m_.z() / 0.3048; }
  double airspeed_ftps() const;
  double alpha_rad() const;
  double beta_rad() const;
  double phi_rad() const { return euler_.x(); }
  double theta_rad() const { return euler_.y(); }
  double psi_rad() const { return euler_.z(); }
  double p_radps() const { return rates_radps_.x(); }

 private:
  using State = Eigen::Matrix<double, 12, 1>;  // pos NED, v body (ground), pqr, euler
  State derivatives(const State &x, const GncOutput &cmd, Eigen::Vector3d *specific_force) const;
  void unpack(const State &x);
  State pack() const;
  void roll_on_ground(double dt_s);
  Eigen::Vector3d air_velocity_body() const;

  SimConfig config_;
  Eigen::Vector3d pos_ned_m_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d vel_body_mps_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d rates_radps_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d euler_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d specific_force_mps2_ = Eigen::Vector3d::Zero();
  bool on_ground_ = false;
  double roll_accel_mps2_ = 0.0;  // 0: parked
  double liftoff_mps_ = 0.0;
  std::mt19937 rng_;
  std::normal_distribution<double> unit_{0.0, 1.0};
};

}  // namespace airframe_sim

#endif
