#include "airdata_ekf.h"

#include <cmath>

#include "dg808_gnc_data.h"

namespace dg808 {
namespace {

// Measurement and process noise of the VN-200 and AMS5812 class sensors this airframe carries.
constexpr double kGpsVelSigmaMps = 0.2;
constexpr double kPitotSigmaMps = 0.5;
constexpr double kAeroZSigmaMps2 = 0.6;  // lift model error and turbulence
constexpr double kAeroYSigmaMps2 = 0.4;
constexpr double kAccelSigmaMps2 = 0.5;    // accelerometer noise plus attitude error leaking g
constexpr double kWindHorizWalkMps = 0.1;  // per sqrt(s)
constexpr double kWindVertWalkMps = 0.05;
constexpr double kInitVelSigmaMps = 1.0;
constexpr double kInitWindHorizSigmaMps = 5.0;
constexpr double kInitWindVertSigmaMps = 3.0;
constexpr double kPi = 3.14159265358979323846;

Eigen::Matrix3d skew(const Eigen::Vector3d &v) {
  Eigen::Matrix3d s;
  s << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return s;
}

}  // namespace

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
  const Eigen::Matrix3d r_nb =
      body_to_ned(first.euler_rad.x(), first.euler_rad.y(), first.euler_rad.z());
  const Eigen::Vector3d v_body = r_nb.transpose() * first.vel_ned_mps;
  // The initial alpha/beta guess is a statement about the air-relative velocity; with the
  // ground velocity known from GPS it becomes an initial wind estimate.
  const double vt = first.airspeed_mps > 0.0 ? first.airspeed_mps : 0.0;
  const Eigen::Vector3d va(vt * std::cos(alpha0_rad) * std::cos(beta0_rad),
                           vt * std::sin(beta0_rad),
                           vt * std::sin(alpha0_rad) * std::cos(beta0_rad));
  x_.head<3>() = v_body;
  x_.tail<3>() = r_nb * (v_body - va);
  p_.setZero();
  p_.diagonal() << kInitVelSigmaMps * kInitVelSigmaMps, kInitVelSigmaMps * kInitVelSigmaMps,
      kInitVelSigmaMps * kInitVelSigmaMps, kInitWindHorizSigmaMps * kInitWindHorizSigmaMps,
      kInitWindHorizSigmaMps * kInitWindHorizSigmaMps,
      kInitWindVertSigmaMps * kInitWindVertSigmaMps;
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
  const Eigen::Vector3d g_body = r_nb.transpose() * Eigen::Vector3d(0.0, 0.0, DG808_GRAVITY_M_S2);
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

  // Chain rule from d/d(va) to d/dx: va = v - R^T W.
  auto to_state = [&r_nb](const Eigen::Vector3d &d_dva) {
    Vec6 h;
    h.head<3>() = d_dva;
    h.tail<3>() = -(r_nb * d_dva);
    return h;
  };

  // Pitot as VT^2: smooth everywhere, including VT = 0. var(VT^2) = 4 VT^2 s^2 + 2 s^4.
  {
    const Eigen::Vector3d va = x_.head<3>() - r_nb.transpose() * x_.tail<3>();
    const double vt_m = m.airspeed_mps > 0.0 ? m.airspeed_mps : 0.0;
    const double s2 = kPitotSigmaMps * kPitotSigmaMps;
    scalar_update(to_state(2.0 * va), vt_m * vt_m - va.squaredNorm(),
                  4.0 * vt_m * vt_m * s2 + 2.0 * s2 * s2);
  }

  // Lift and side force: only in flight; on the ground the wheels, not the wings, carry the
  // weight. Written as polynomials in va (small-angle forms of CL*qbar, CY*qbar).
  if (m.airspeed_mps >= config_.airspeed_valid_min_mps) {
    const double k = DG808_AIR_DENSITY_KG_M3 * DG808_WING_AREA_M2 / (2.0 * DG808_MASS_KG);
    const double half_c = 0.5 * DG808_MEAN_CHORD_M;
    const double cl0 = DG808_CL0 + DG808_CL_ELEVATOR_PER_RAD * m.elevator_rad;
    Eigen::Vector3d va = x_.head<3>() - r_nb.transpose() * x_.tail<3>();
    const double fz = -k * (cl0 * va.squaredNorm() + DG808_CL_ALPHA_PER_RAD * va.x() * va.z() +
                            DG808_CL_Q_PER_RAD * half_c * m.rates_radps.y() * va.x());
    const Eigen::Vector3d dfz =
        -k * (2.0 * cl0 * va + DG808_CL_ALPHA_PER_RAD * Eigen::Vector3d(va.z(), 0.0, va.x()) +
              DG808_CL_Q_PER_RAD * half_c * m.rates_radps.y() * Eigen::Vector3d::UnitX());
    scalar_update(to_state(dfz), m.specific_force_mps2.z() - fz, kAeroZSigmaMps2 * kAeroZSigmaMps2);

    va = x_.head<3>() - r_nb.transpose() * x_.tail<3>();
    const double cydr = DG808_CY_RUDDER_PER_RAD * m.rudder_rad;
    const double fy = k * (DG808_CY_BETA_PER_RAD * va.x() * va.y() + cydr * va.squaredNorm());
    const Eigen::Vector3d dfy =
        k * (DG808_CY_BETA_PER_RAD * Eigen::Vector3d(va.y(), va.x(), 0.0) + 2.0 * cydr * va);
    scalar_update(to_state(dfy), m.specific_force_mps2.y() - fy, kAeroYSigmaMps2 * kAeroYSigmaMps2);
  }
  p_ = 0.5 * (p_ + p_.transpose());
  return estimate(r_nb, m.airspeed_mps);
}

AirdataEstimate AirdataEkf::peek(const AirdataMeasurement &m) const {
  return estimate(body_to_ned(m.euler_rad.x(), m.euler_rad.y(), m.euler_rad.z()), m.airspeed_mps);
}

AirdataEstimate AirdataEkf::estimate(const Eigen::Matrix3d &r_nb,
                                     double measured_airspeed_mps) const {
  AirdataEstimate e;
  const Eigen::Vector3d va = x_.head<3>() - r_nb.transpose() * x_.tail<3>();
  e.vt_mps = va.norm();
  e.alpha_rad = std::atan2(va.z(), va.x());
  e.beta_rad = std::atan2(va.y(), std::hypot(va.x(), va.z()));
  e.wind_ned_mps = x_.tail<3>();
  Eigen::Matrix<double, 3, 6> j;
  j.leftCols<3>() = Eigen::Matrix3d::Identity();
  j.rightCols<3>() = -r_nb.transpose();
  const Eigen::Matrix3d cov_va = j * p_ * j.transpose();
  // Uncertainty of the air-velocity direction: the variance across va in the alpha and beta
  // directions, over |va|. Only defined once there is airflow to have a direction.
  const double sa = std::sin(e.alpha_rad), ca = std::cos(e.alpha_rad);
  const double sb = std::sin(e.beta_rad), cb = std::cos(e.beta_rad);
  const bool flowing = e.vt_mps * cb >= config_.airspeed_valid_min_mps &&
                       measured_airspeed_mps >= config_.airspeed_valid_min_mps;
  if (flowing) {
    const Eigen::Vector3d e_alpha(-sa, 0.0, ca);
    const Eigen::Vector3d e_beta(-ca * sb, cb, -sa * sb);
    const double v_perp_alpha = e.vt_mps * cb;  // >= vmin > 0 (checked above)
    e.alpha_sigma_rad = std::sqrt(e_alpha.dot(cov_va * e_alpha)) / v_perp_alpha;
    e.beta_sigma_rad = std::sqrt(e_beta.dot(cov_va * e_beta)) / e.vt_mps;
    e.converged = e.alpha_sigma_rad <= config_.converged_sigma_rad &&
                  e.beta_sigma_rad <= config_.converged_sigma_rad;
  } else {
    e.alpha_sigma_rad = kPi;
    e.beta_sigma_rad = kPi;
    e.converged = false;
  }
  return e;
}

}  // namespace dg808
