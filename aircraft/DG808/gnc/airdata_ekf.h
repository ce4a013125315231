// Extended Kalman filter for true airspeed, angle of attack, sideslip and wind.
//
// State: body-axis ground velocity [u v w] and the air mass velocity [Wn We Wd], m/s. The
// air-relative velocity is va = [u v w] - R^T W. Measurements: GPS NED velocity, the pitot's
// airspeed as VT^2 = |va|^2, and (in flight) the body specific force predicted by the lift and
// side-force model. Every measurement is a polynomial in the state, so the filter has no
// division by the airspeed: at zero airspeed the Jacobians simply vanish and the filter stays
// finite (the thesis's NaN on the ground came from dividing by VT). Alpha and beta come from
// atan2, which is defined everywhere.
#ifndef DG808_AIRDATA_EKF_H
#define DG808_AIRDATA_EKF_H

#include <Eigen/Dense>

namespace dg808 {

struct AirdataMeasurement {
  Eigen::Vector3d vel_ned_mps;
  Eigen::Vector3d rates_radps;
  Eigen::Vector3d specific_force_mps2;
  Eigen::Vector3d euler_rad;  // phi, theta, psi
  double airspeed_mps;
  double elevator_rad;
  double rudder_rad;
};

struct AirdataEstimate {
  double vt_mps = 0.0;
  double alpha_rad = 0.0;
  double beta_rad = 0.0;
  double alpha_sigma_rad = 0.0;
  double beta_sigma_rad = 0.0;
  Eigen::Vector3d wind_ned_mps = Eigen::Vector3d::Zero();
  bool converged = false;
};

class AirdataEkf {
 public:
  struct Config {
    double airspeed_valid_min_mps;  // below: alpha/beta undefined, aero measurements unused
    double converged_sigma_rad;
  };

  void reset(const Config &config, const AirdataMeasurement &first, double alpha0_rad,
             double beta0_rad);
  AirdataEstimate step(const AirdataMeasurement &m, double dt_s);
  // The current estimate seen with this attitude, without a filter update.
  AirdataEstimate peek(const AirdataMeasurement &m) const;

 private:
  using Vec6 = Eigen::Matrix<double, 6, 1>;
  using Mat6 = Eigen::Matrix<double, 6, 6>;
  void scalar_update(const Vec6 &h, double innovation, double variance);
  AirdataEstimate estimate(const Eigen::Matrix3d &r_nb, double measured_airspeed_mps) const;

  Config config_{};
  Vec6 x_ = Vec6::Zero();
  Mat6 p_ = Mat6::Identity();
};

Eigen::Matrix3d body_to_ned(double phi, double theta, double psi);

}  // namespace dg808

#endif
