// Extended Kalman filter for true airspeed, angle of attack, sideslip and wind.
//
// State: body-axis ground velocity [u v w] and the air mass velocity [Wn We Wd], m/s. The
// air-relative velocity is va = [u v w] - R^T W. Measurements: GPS NED velocity, the pitot's
// airspeed as VT^2 = |va|^2 and, while the wing carries the aircraft, the body specific force
// predicted by the lift and side-force models. GPS and the pitot are polynomials in the state
// and the filter never divides by the airspeed on the ground (the thesis's NaN there came from
// dividing by VT); alpha and beta come from atan2, defined everywhere.
//
// Which way the air flows. The pitot gives |va| only: a parked aircraft in a wind, or one flying
// straight, cannot tell from it where the wind blows from. In flight the lift and side force
// tell alpha and beta, so the air direction is observable on any heading, but only if those
// models are written in the angles: as polynomials (CL_alpha vx vz, CY_beta vx vy) they fold at
// 45 deg, and alpha 88 deg explains the lift of alpha 2 deg (the estimator then reported
// converged at alpha 80-87 and beta +-55 deg in the HiL's headwind, and the HA rightly never
// handed over). So:
// - On the ground (the wheels carry the weight; the GNC decides, AirdataMeasurement::wing_borne)
//   there is no aero measurement and no claim: the air is taken to come along the nose at the
//   configured guess (alpha0, beta0), i.e. the wind is the pitot's reading on the nose, at the
//   initial uncertainty.
// - Airborne, the lift and side force are measured in alpha and beta themselves (monotonic: one
//   solution), and the same models solved directly for alpha and beta from this step's pitot and
//   accelerometer are the check: an estimate off the physical branch (|alpha| or |beta| beyond
//   45 deg), or away from the direct solution (low-passed) by kReinitGapDeg, is started over from
//   the direct solution; leaving the ground starts from it too.
// - Converged is claimed only airborne, with the 1-sigma of alpha and beta below the configured
//   bound and the estimate agreeing with the direct solution.
#ifndef GNC_AIRDATA_EKF_H
#define GNC_AIRDATA_EKF_H

#include <Eigen/Dense>

namespace gnc {

struct AirdataMeasurement {
  Eigen::Vector3d vel_ned_mps;
  Eigen::Vector3d rates_radps;
  Eigen::Vector3d specific_force_mps2;
  Eigen::Vector3d euler_rad;  // phi, theta, psi
  double airspeed_mps;
  double elevator_rad;
  double rudder_rad;
  bool wing_borne = false;  // airborne: the lift and side-force models apply
};

struct AirdataEstimate {
  double vt_mps = 0.0;
  double alpha_rad = 0.0;
  double beta_rad = 0.0;
  double alpha_sigma_rad = 0.0;
  double beta_sigma_rad = 0.0;
  Eigen::Vector3d wind_ned_mps = Eigen::Vector3d::Zero();
  bool converged = false;
  // Airborne: the direct solution of the lift and side-force models this estimate was checked
  // against, and how many times the estimate was started over from it.
  bool consistent = false;
  int restarts = 0;
};

class AirdataEkf {
 public:
  struct Config {
    double airspeed_valid_min_mps;  // below: alpha/beta undefined, aero measurements unused
    double converged_sigma_rad;
    double stall_speed_mps;  // 1 g: from here up the wing can carry the weight (direct solution)
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
  // Airborne: the pitot, then the lift and side force.
  void airborne_updates(const Eigen::Matrix3d &r_nb, const AirdataMeasurement &m);
  // Sets the wind so that the air comes at the measured airspeed from (alpha, beta), with the
  // given 1-sigma on the wind and no correlation left with the velocity.
  void assume_air_from(const Eigen::Matrix3d &r_nb, const AirdataMeasurement &m, double alpha_rad,
                       double beta_rad, double wind_horiz_sigma_mps, double wind_vert_sigma_mps);
  // Airborne: compares with the direct solution and starts over from it when off the branch.
  void check_branch(const Eigen::Matrix3d &r_nb, const AirdataMeasurement &m, double dt_s);
  AirdataEstimate estimate(const Eigen::Matrix3d &r_nb, double measured_airspeed_mps) const;

  Config config_{};
  Vec6 x_ = Vec6::Zero();
  Mat6 p_ = Mat6::Identity();
  double alpha0_rad_ = 0.0, beta0_rad_ = 0.0;
  bool wing_borne_ = false;  // the last step's
  bool was_on_ground_ = false;
  bool gap_valid_ = false;  // the low-passed gaps below hold a value
  double alpha_gap_rad_ = 0.0, beta_gap_rad_ = 0.0;
  double gap_age_s_ = 0.0;    // how long the gaps have been low-passed since the last start
  double pitot_age_s_ = 0.0;  // airborne: since the last pitot reading above the valid minimum
  bool consistent_ = false;
  int restarts_ = 0;
};

// Alpha and beta that the lift and side-force models give for this step's airspeed (pitot),
// specific force (accelerometer), pitch rate and surfaces; false when the airspeed is below the
// stall speed (the wing cannot carry the weight; the linear models say nothing). Clamped to
// +-30 deg: a start-over point on the physical branch.
bool direct_air_angles(const AirdataMeasurement &m, double stall_speed_mps, double *alpha_rad,
                       double *beta_rad);

Eigen::Matrix3d body_to_ned(double phi, double theta, double psi);

}  // namespace gnc

#endif
