#include "airdata_ekf.h"

#include <algorithm>
#include <cmath>

#include "gnc_aircraft.h"

namespace gnc {
namespace {

// Measurement and process noise of the VN-200 and AMS5812 class sensors this airframe carries.
constexpr double kGpsVelSigmaMps = 0.2;
constexpr double kPitotSigmaMps = 0.5;
constexpr double kAeroZSigmaMps2 = 0.6;  // lift model error and turbulence
constexpr double kAeroYSigmaMps2 = 0.4;
constexpr double kAccelSigmaMps2 = 0.5;    // accelerometer noise plus attitude error leaking g
constexpr double kWindHorizWalkMps = 0.5;  // per sqrt(s)
constexpr double kWindVertWalkMps = 0.3;
constexpr double kInitVelSigmaMps = 1.0;
constexpr double kInitWindHorizSigmaMps = 5.0;
constexpr double kInitWindVertSigmaMps = 3.0;
// Started over from the direct solution airborne: its alpha and beta carry the lift model's error
// and the side-force noise (a few deg at flying speeds, so about 1 m/s across the air velocity).
constexpr double kRestartWindHorizSigmaMps = 2.0;
constexpr double kRestartWindVertSigmaMps = 1.0;
constexpr double kPi = 3.14159265358979323846;
constexpr double kDegToRad = kPi / 180.0;
// The lift and side-force polynomials of the state folded at 45 deg; the physical branch of a
// flying wing lies well inside it (stall at 8.85 deg, the HA's own limit 30 deg).
constexpr double kBranchLimitRad = 45.0 * kDegToRad;
// The estimate against the direct solution, both low-passed over kGapTauS (turbulence moves the
// direct solution at once, the estimate's wind slowly): within kConsistentGapDeg it may claim
// convergence; beyond kReinitGapDeg it is on a wrong branch and starts over.
constexpr double kGapTauS = 1.0;
constexpr double kConsistentGapRad = 6.0 * kDegToRad;
constexpr double kReinitGapRad = 15.0 * kDegToRad;
constexpr double kDirectClampRad = 30.0 * kDegToRad;
// Airborne, a pitot dropout this short keeps the claim: the estimate coasts on the IMU and GPS and
// its 1-sigma still has to hold (the HiL's HA sends 0 for 1 to 6 periods while it lacks its own
// state; dropping the claim for that made it restart a healthy HP).
constexpr double kPitotHoldS = 0.5;

Eigen::Matrix3d skew(const Eigen::Vector3d &v) {
  Eigen::Matrix3d s;
  s << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return s;
}

// k = rho S / (2 m): specific force per (lift coefficient x airspeed^2).
constexpr double kLiftPerClV2 =
    AIRFRAME_AIR_DENSITY_KG_M3 * AIRFRAME_WING_AREA_M2 / (2.0 * AIRFRAME_MASS_KG);

double wrap_pi(double a) { return std::atan2(std::sin(a), std::cos(a)); }

}  // namespace

bool direct_air_angles(const AirdataMeasurement &m, double stall_speed_mps, double *alpha_rad,
                       double *beta_rad) {
  const double vt = m.airspeed_mps;
  if (!(vt >= stall_speed_mps) || vt <= 0.0) {
    return false;
  }
  const double kv2 = kLiftPerClV2 * vt * vt;
  // fz = -k V^2 (CL0 + CLde de + CLa alpha) - k CLq (c/2) q V, solved for alpha.
  const double cl = -m.specific_force_mps2.z() / kv2;
  const double alpha =
      (cl - AIRFRAME_CL0 - AIRFRAME_CL_ELEVATOR_PER_RAD * m.elevator_rad -
       AIRFRAME_CL_Q_PER_RAD * 0.5 * AIRFRAME_MEAN_CHORD_M * m.rates_radps.y() / vt) /
      AIRFRAME_CL_ALPHA_PER_RAD;
  // fy = k V^2 (CYb beta + CYdr dr), solved for beta.
  const double beta =
      (m.specific_force_mps2.y() / kv2 - AIRFRAME_CY_RUDDER_PER_RAD * m.rudder_rad) /
      AIRFRAME_CY_BETA_PER_RAD;
  *alpha_rad = std::clamp(alpha, -kDirectClampRad, kDirectClampRad);
  *beta_rad = std::clamp(beta, -kDirectClampRad, kDirectClampRad);
  return true;
}

Eigen::Matrix3d body_to_ned(double phi, double theta, double psi) {
  const double cf = std::cos(phi), sf = std::sin(phi);
  const double ct = std::cos(theta), st = std::sin(theta);
  const double cp = std::cos(psi), sp = std::sin(psi);
  Eigen::Matrix3d r;
  r << ct * cp, sf * st * cp - cf * sp, cf * st * cp + sf * sp, ct * sp, sf * st * sp + cf * cp,
      cf * st * sp - sf * cp, -st, sf * ct, cf * ct;
  return r;
}

void AirdataEkf::reset(const Config &config, const AirdataMeasurement &first, double alpha0_rad,
                       double beta0_rad) {
  config_ = config;
  alpha0_rad_ = alpha0_rad;
  beta0_rad_ = beta0_rad;
  wing_borne_ = first.wing_borne;
  was_on_ground_ = !first.wing_borne;
  gap_valid_ = false;
  consistent_ = false;
  restarts_ = 0;
  const Eigen::Matrix3d r_nb =
      body_to_ned(first.euler_rad.x(), first.euler_rad.y(), first.euler_rad.z());
  x_.head<3>() = r_nb.transpose() * first.vel_ned_mps;
  p_.setZero();
  p_.diagonal().head<3>().setConstant(kInitVelSigmaMps * kInitVelSigmaMps);
  // The initial alpha/beta guess is a statement about the air-relative velocity; with the
  // ground velocity known from GPS it becomes an initial wind estimate.
  assume_air_from(r_nb, first, alpha0_rad, beta0_rad, kInitWindHorizSigmaMps,
                  kInitWindVertSigmaMps);
}

void AirdataEkf::assume_air_from(const Eigen::Matrix3d &r_nb, const AirdataMeasurement &m,
                                 double alpha_rad, double beta_rad, double wind_horiz_sigma_mps,
                                 double wind_vert_sigma_mps) {
  const double vt = m.airspeed_mps > 0.0 ? m.airspeed_mps : 0.0;
  const Eigen::Vector3d va(vt * std::cos(alpha_rad) * std::cos(beta_rad), vt * std::sin(beta_rad),
                           vt * std::sin(alpha_rad) * std::cos(beta_rad));
  x_.tail<3>() = r_nb * (x_.head<3>() - va);
  p_.bottomRows<3>().setZero();
  p_.rightCols<3>().setZero();
  p_.diagonal().tail<3>() << wind_horiz_sigma_mps * wind_horiz_sigma_mps,
      wind_horiz_sigma_mps * wind_horiz_sigma_mps, wind_vert_sigma_mps * wind_vert_sigma_mps;
}

void AirdataEkf::scalar_update(const Vec6 &h, double innovation, double variance) {
  // Joseph form keeps P symmetric positive definite; variance > 0 so s > 0.
  const double s = h.dot(p_ * h) + variance;
  const Vec6 k = p_ * h / s;
  x_ += k * innovation;
  const Mat6 i_kh = Mat6::Identity() - k * h.transpose();
  p_ = i_kh * p_ * i_kh.transpose() + k * variance * k.transpose();
}

AirdataEstimate AirdataEkf::step(const AirdataMeasurement &m, double dt_s) {
  const Eigen::Matrix3d r_nb = body_to_ned(m.euler_rad.x(), m.euler_rad.y(), m.euler_rad.z());
  const Eigen::Vector3d &w = m.rates_radps;

  // Predict: rigid-body kinematics driven by the IMU; the wind is a random walk.
  const Eigen::Vector3d g_body =
      r_nb.transpose() * Eigen::Vector3d(0.0, 0.0, AIRFRAME_GRAVITY_M_S2);
  const Eigen::Vector3d v = x_.head<3>();
  x_.head<3>() = v + dt_s * (m.specific_force_mps2 + g_body - w.cross(v));
  Mat6 f = Mat6::Identity();
  f.topLeftCorner<3, 3>() -= dt_s * skew(w);
  Mat6 q = Mat6::Zero();
  q.diagonal() << kAccelSigmaMps2 * kAccelSigmaMps2 * dt_s,
      kAccelSigmaMps2 * kAccelSigmaMps2 * dt_s, kAccelSigmaMps2 * kAccelSigmaMps2 * dt_s,
      kWindHorizWalkMps * kWindHorizWalkMps * dt_s, kWindHorizWalkMps * kWindHorizWalkMps * dt_s,
      kWindVertWalkMps * kWindVertWalkMps * dt_s;
  p_ = f * p_ * f.transpose() + q;

  // GPS velocity, one axis at a time.
  for (int i = 0; i < 3; ++i) {
    Vec6 h = Vec6::Zero();
    h.head<3>() = r_nb.row(i).transpose();
    const double predicted = r_nb.row(i).dot(x_.head<3>());
    scalar_update(h, m.vel_ned_mps(i) - predicted, kGpsVelSigmaMps * kGpsVelSigmaMps);
  }

  if (!m.wing_borne) {
    // On the wheels: no aero measurement holds (the wheels carry the weight and the side load),
    // and the pitot tells how fast the wind blows, not where from. The air is taken to come at
    // the guess along the nose; alpha and beta are not claimed (estimate()).
    assume_air_from(r_nb, m, alpha0_rad_, beta0_rad_, kInitWindHorizSigmaMps,
                    kInitWindVertSigmaMps);
    wing_borne_ = false;
    was_on_ground_ = true;
    gap_valid_ = false;
    consistent_ = false;
    p_ = 0.5 * (p_ + p_.transpose());
    return estimate(r_nb, m.airspeed_mps);
  }
  if (was_on_ground_) {
    // Just off the ground: what the wheels hid, the lift and side force now tell.
    double alpha = 0.0, beta = 0.0;
    if (direct_air_angles(m, config_.stall_speed_mps, &alpha, &beta)) {
      assume_air_from(r_nb, m, alpha, beta, kRestartWindHorizSigmaMps, kRestartWindVertSigmaMps);
      was_on_ground_ = false;
    }
  }
  wing_borne_ = true;
  pitot_age_s_ += dt_s;
  airborne_updates(r_nb, m);
  check_branch(r_nb, m, dt_s);
  p_ = 0.5 * (p_ + p_.transpose());
  return estimate(r_nb, m.airspeed_mps);
}

void AirdataEkf::airborne_updates(const Eigen::Matrix3d &r_nb, const AirdataMeasurement &m) {
  // Chain rule from d/d(va) to d/dx: va = v - R^T W.
  auto to_state = [&r_nb](const Eigen::Vector3d &d_dva) {
    Vec6 h;
    h.head<3>() = d_dva;
    h.tail<3>() = -(r_nb * d_dva);
    return h;
  };

  // Airborne, a reading below the valid minimum is a pitot that dropped out (the wing cannot fly
  // that slowly): no air data this step; the estimate coasts on the IMU and GPS.
  if (m.airspeed_mps < config_.airspeed_valid_min_mps) {
    return;
  }
  pitot_age_s_ = 0.0;
  // Pitot as VT^2: smooth everywhere, no division by VT. var(VT^2) = 4 VT^2 s^2 + 2 s^4.
  {
    const Eigen::Vector3d va = x_.head<3>() - r_nb.transpose() * x_.tail<3>();
    const double vt_m = m.airspeed_mps;
    const double s2 = kPitotSigmaMps * kPitotSigmaMps;
    scalar_update(to_state(2.0 * va), vt_m * vt_m - va.squaredNorm(),
                  4.0 * vt_m * vt_m * s2 + 2.0 * s2 * s2);
  }
  // Lift and side force, written in alpha and beta themselves (CL = CL0 + CLa alpha + ...,
  // CY = CYb beta + ...): monotonic in the angles, so one air direction explains them, where the
  // polynomial forms (vx vz, vx vy) folded at 45 deg. The angles need the airflow's x-z part to
  // be more than the valid minimum; below it there is no direction to measure.
  const double k = kLiftPerClV2;
  const double half_c = 0.5 * AIRFRAME_MEAN_CHORD_M;
  const double vmin2 = config_.airspeed_valid_min_mps * config_.airspeed_valid_min_mps;
  {
    const Eigen::Vector3d va = x_.head<3>() - r_nb.transpose() * x_.tail<3>();
    const double sxz = va.x() * va.x() + va.z() * va.z();
    if (sxz < vmin2) {
      return;
    }
    const double v2 = va.squaredNorm();
    const double alpha = std::atan2(va.z(), va.x());
    const Eigen::Vector3d dalpha = Eigen::Vector3d(-va.z(), 0.0, va.x()) / sxz;
    const double cl0 = AIRFRAME_CL0 + AIRFRAME_CL_ELEVATOR_PER_RAD * m.elevator_rad;
    const double fz = -k * (cl0 * v2 + AIRFRAME_CL_ALPHA_PER_RAD * v2 * alpha +
                            AIRFRAME_CL_Q_PER_RAD * half_c * m.rates_radps.y() * va.x());
    const Eigen::Vector3d dfz =
        -k * (2.0 * cl0 * va + AIRFRAME_CL_ALPHA_PER_RAD * (2.0 * alpha * va + v2 * dalpha) +
              AIRFRAME_CL_Q_PER_RAD * half_c * m.rates_radps.y() * Eigen::Vector3d::UnitX());
    scalar_update(to_state(dfz), m.specific_force_mps2.z() - fz, kAeroZSigmaMps2 * kAeroZSigmaMps2);
  }
  {
    const Eigen::Vector3d va = x_.head<3>() - r_nb.transpose() * x_.tail<3>();
    const double sxz = va.x() * va.x() + va.z() * va.z();
    if (sxz < vmin2) {
      return;
    }
    const double v2 = va.squaredNorm();
    const double rxz = std::sqrt(sxz);
    const double beta = std::atan2(va.y(), rxz);
    const Eigen::Vector3d dbeta =
        Eigen::Vector3d(-va.x() * va.y(), sxz, -va.z() * va.y()) / (v2 * rxz);
    const double cydr = AIRFRAME_CY_RUDDER_PER_RAD * m.rudder_rad;
    const double fy = k * (AIRFRAME_CY_BETA_PER_RAD * v2 * beta + cydr * v2);
    const Eigen::Vector3d dfy =
        k * (AIRFRAME_CY_BETA_PER_RAD * (2.0 * beta * va + v2 * dbeta) + 2.0 * cydr * va);
    scalar_update(to_state(dfy), m.specific_force_mps2.y() - fy, kAeroYSigmaMps2 * kAeroYSigmaMps2);
  }
}

void AirdataEkf::check_branch(const Eigen::Matrix3d &r_nb, const AirdataMeasurement &m,
                              double dt_s) {
  double alpha_d = 0.0, beta_d = 0.0;
  if (!direct_air_angles(m, config_.stall_speed_mps, &alpha_d, &beta_d)) {
    return;  // below the stall speed the models say nothing: the last verdict stands
  }
  const Eigen::Vector3d va = x_.head<3>() - r_nb.transpose() * x_.tail<3>();
  const double alpha = std::atan2(va.z(), va.x());
  const double beta = std::atan2(va.y(), std::hypot(va.x(), va.z()));
  const double alpha_gap = wrap_pi(alpha - alpha_d), beta_gap = wrap_pi(beta - beta_d);
  if (gap_valid_) {
    gap_age_s_ += dt_s;
    const double a = std::min(1.0, dt_s / kGapTauS);
    alpha_gap_rad_ += a * (alpha_gap - alpha_gap_rad_);
    beta_gap_rad_ += a * (beta_gap - beta_gap_rad_);
  } else {
    alpha_gap_rad_ = alpha_gap;
    beta_gap_rad_ = beta_gap;
    gap_valid_ = true;
    gap_age_s_ = 0.0;
  }
  const bool off_branch = std::fabs(alpha) > kBranchLimitRad || std::fabs(beta) > kBranchLimitRad;
  if (off_branch || std::fabs(alpha_gap_rad_) > kReinitGapRad ||
      std::fabs(beta_gap_rad_) > kReinitGapRad) {
    assume_air_from(r_nb, m, alpha_d, beta_d, kRestartWindHorizSigmaMps, kRestartWindVertSigmaMps);
    ++restarts_;
    gap_valid_ = false;
    consistent_ = false;
    return;
  }
  // Agreeing over a whole time constant, not on the first steps after a start: the 1-sigma a
  // fresh start reports shrinks within a few steps, faster than the side force's noise averages.
  consistent_ = gap_age_s_ >= kGapTauS && std::fabs(alpha_gap_rad_) <= kConsistentGapRad &&
                std::fabs(beta_gap_rad_) <= kConsistentGapRad;
}

AirdataEstimate AirdataEkf::peek(const AirdataMeasurement &m) const {
  return estimate(body_to_ned(m.euler_rad.x(), m.euler_rad.y(), m.euler_rad.z()), m.airspeed_mps);
}

AirdataEstimate AirdataEkf::estimate(const Eigen::Matrix3d &r_nb,
                                     double measured_airspeed_mps) const {
  AirdataEstimate e;
  const Eigen::Vector3d va = x_.head<3>() - r_nb.transpose() * x_.tail<3>();
  e.vt_mps = va.norm();
  // Air slower than the valid minimum has no direction worth a number: the guess stands in (parked
  // in calm air atan2 of rounding noise read anything up to 180 deg).
  const bool directed = e.vt_mps >= config_.airspeed_valid_min_mps;
  e.alpha_rad = directed ? std::atan2(va.z(), va.x()) : alpha0_rad_;
  e.beta_rad = directed ? std::atan2(va.y(), std::hypot(va.x(), va.z())) : beta0_rad_;
  e.wind_ned_mps = x_.tail<3>();
  e.consistent = wing_borne_ && consistent_;
  e.restarts = restarts_;
  Eigen::Matrix<double, 3, 6> j;
  j.leftCols<3>() = Eigen::Matrix3d::Identity();
  j.rightCols<3>() = -r_nb.transpose();
  const Eigen::Matrix3d cov_va = j * p_ * j.transpose();
  // Uncertainty of the air-velocity direction: the variance across va in the alpha and beta
  // directions, over |va|. Only defined once there is airflow to have a direction.
  const double sa = std::sin(e.alpha_rad), ca = std::cos(e.alpha_rad);
  const double sb = std::sin(e.beta_rad), cb = std::cos(e.beta_rad);
  const bool measured = measured_airspeed_mps >= config_.airspeed_valid_min_mps ||
                        (wing_borne_ && pitot_age_s_ <= kPitotHoldS);
  const bool flowing = e.vt_mps * cb >= config_.airspeed_valid_min_mps && measured;
  if (flowing) {
    const Eigen::Vector3d e_alpha(-sa, 0.0, ca);
    const Eigen::Vector3d e_beta(-ca * sb, cb, -sa * sb);
    const double v_perp_alpha = e.vt_mps * cb;  // >= vmin > 0 (checked above)
    e.alpha_sigma_rad = std::sqrt(e_alpha.dot(cov_va * e_alpha)) / v_perp_alpha;
    e.beta_sigma_rad = std::sqrt(e_beta.dot(cov_va * e_beta)) / e.vt_mps;
    e.converged = e.consistent && e.alpha_sigma_rad <= config_.converged_sigma_rad &&
                  e.beta_sigma_rad <= config_.converged_sigma_rad;
  } else {
    e.alpha_sigma_rad = kPi;
    e.beta_sigma_rad = kPi;
    e.converged = false;
  }
  return e;
}

}  // namespace gnc
