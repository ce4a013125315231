#include "airframe_sim.h"

#include <algorithm>
#include <cmath>

#include "geo_wgs84.h"
#include "gnc_aircraft.h"

namespace airframe_sim {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kFtPerM = 1.0 / 0.3048;

Eigen::Matrix3d body_to_ned(const Eigen::Vector3d &e) {
  const double cf = std::cos(e.x()), sf = std::sin(e.x());
  const double ct = std::cos(e.y()), st = std::sin(e.y());
  const double cp = std::cos(e.z()), sp = std::sin(e.z());
  Eigen::Matrix3d r;
  r << ct * cp, sf * st * cp - cf * sp, cf * st * cp + sf * sp, ct * sp, sf * st * sp + cf * cp,
      cf * st * sp - sf * cp, -st, sf * ct, cf * ct;
  return r;
}

}  // namespace

Sim::Sim(const SimConfig &config) : config_(config), rng_(config.seed) {}

void Sim::set_trimmed_flight(double airspeed_ftps, double height_ft, double psi_rad) {
  on_ground_ = false;
  const double vt = airspeed_ftps / kFtPerM;
  pos_ned_m_ = Eigen::Vector3d(0.0, 0.0, -height_ft / kFtPerM);
  euler_ = Eigen::Vector3d(0.0, GNC_TRIM_THETA_RAD, psi_rad);
  rates_radps_.setZero();
  const Eigen::Vector3d va(vt * std::cos(GNC_TRIM_ALPHA_RAD), 0.0,
                           vt * std::sin(GNC_TRIM_ALPHA_RAD));
  vel_body_mps_ = va + body_to_ned(euler_).transpose() * config_.wind_ned_mps;
  specific_force_mps2_ = Eigen::Vector3d(0.0, 0.0, -AIRFRAME_GRAVITY_M_S2);
}

void Sim::set_on_ground(double psi_rad) {
  on_ground_ = true;
  roll_accel_mps2_ = 0.0;
  pos_ned_m_.setZero();
  vel_body_mps_.setZero();
  rates_radps_.setZero();
  euler_ = Eigen::Vector3d(0.0, 0.0, psi_rad);
  specific_force_mps2_ = Eigen::Vector3d(0.0, 0.0, -AIRFRAME_GRAVITY_M_S2);
}

void Sim::start_takeoff_roll(double accel_mps2, double liftoff_ftps) {
  roll_accel_mps2_ = accel_mps2;
  liftoff_mps_ = liftoff_ftps / kFtPerM;
}

void Sim::roll_on_ground(double dt_s) {
  if (roll_accel_mps2_ <= 0.0) {
    return;  // parked
  }
  const Eigen::Matrix3d r_nb = body_to_ned(euler_);
  vel_body_mps_ = Eigen::Vector3d(vel_body_mps_.x() + roll_accel_mps2_ * dt_s, 0.0, 0.0);
  pos_ned_m_ += r_nb * vel_body_mps_ * dt_s;
  specific_force_mps2_ = Eigen::Vector3d(roll_accel_mps2_, 0.0, -AIRFRAME_GRAVITY_M_S2);
  const Eigen::Vector3d va_ned = r_nb * vel_body_mps_ - config_.wind_ned_mps;
  const double vt = va_ned.norm();
  if (vt < liftoff_mps_) {
    return;
  }
  // Off the wheels: level, the nose into the relative wind (the ground track is kept), at the
  // angle of attack whose lift carries the weight at this airspeed.
  const double cl = 2.0 * AIRFRAME_MASS_KG * config_.mass_scale * AIRFRAME_GRAVITY_M_S2 /
                    (AIRFRAME_AIR_DENSITY_KG_M3 * AIRFRAME_WING_AREA_M2 * vt * vt);
  const double alpha = (cl - AIRFRAME_CL0) / AIRFRAME_CL_ALPHA_PER_RAD;
  on_ground_ = false;
  roll_accel_mps2_ = 0.0;
  euler_ = Eigen::Vector3d(0.0, alpha, std::atan2(va_ned.y(), va_ned.x()));
  vel_body_mps_ = vt * Eigen::Vector3d(std::cos(alpha), 0.0, std::sin(alpha)) +
                  body_to_ned(euler_).transpose() * config_.wind_ned_mps;
  specific_force_mps2_ = Eigen::Vector3d(0.0, 0.0, -AIRFRAME_GRAVITY_M_S2);
}

Eigen::Vector3d Sim::air_velocity_body() const {
  return vel_body_mps_ - body_to_ned(euler_).transpose() * config_.wind_ned_mps;
}

double Sim::airspeed_ftps() const { return air_velocity_body().norm() * kFtPerM; }

double Sim::alpha_rad() const {
  const Eigen::Vector3d va = air_velocity_body();
  return std::atan2(va.z(), va.x());
}

double Sim::beta_rad() const {
  const Eigen::Vector3d va = air_velocity_body();
  const double vt = va.norm();
  return vt > 0.0 ? std::asin(va.y() / vt) : 0.0;
}

Sim::State Sim::pack() const {
  State x;
  x << pos_ned_m_, vel_body_mps_, rates_radps_, euler_;
  return x;
}

void Sim::unpack(const State &x) {
  pos_ned_m_ = x.segment<3>(0);
  vel_body_mps_ = x.segment<3>(3);
  rates_radps_ = x.segment<3>(6);
  euler_ = x.segment<3>(9);
}

Sim::State Sim::derivatives(const State &x, const GncOutput &cmd,
                            Eigen::Vector3d *specific_force) const {
  const Eigen::Vector3d v = x.segment<3>(3);
  const Eigen::Vector3d w = x.segment<3>(6);
  const Eigen::Vector3d e = x.segment<3>(9);
  const Eigen::Matrix3d r_nb = body_to_ned(e);
  const Eigen::Vector3d va = v - r_nb.transpose() * config_.wind_ned_mps;
  const double vt = va.norm();
  const double alpha = std::atan2(va.z(), va.x());
  const double beta = std::asin(va.y() / vt);
  const double qbar = 0.5 * AIRFRAME_AIR_DENSITY_KG_M3 * vt * vt;
  const double phat = w.x() * AIRFRAME_WING_SPAN_M / (2.0 * vt);
  const double qhat = w.y() * AIRFRAME_MEAN_CHORD_M / (2.0 * vt);
  const double rhat = w.z() * AIRFRAME_WING_SPAN_M / (2.0 * vt);
  const double k = config_.control_power_scale;
  const double de = k * cmd.elevator_rad, da = k * cmd.aileron_rad, dr = k * cmd.rudder_rad;
  const double cl = AIRFRAME_CL0 + AIRFRAME_CL_ALPHA_PER_RAD * alpha +
                    AIRFRAME_CL_Q_PER_RAD * qhat + AIRFRAME_CL_ELEVATOR_PER_RAD * de;
  const double cd = config_.drag_scale * (AIRFRAME_CD0 + AIRFRAME_CD_K * cl * cl);
  const double cy = AIRFRAME_CY_BETA_PER_RAD * beta + AIRFRAME_CY_RUDDER_PER_RAD * dr;
  const double croll = AIRFRAME_CL_BETA_PER_RAD * beta + AIRFRAME_CL_P_PER_RAD * phat +
                       AIRFRAME_CL_R_PER_RAD * rhat + AIRFRAME_CL_AILERON_PER_RAD * da +
                       AIRFRAME_CL_RUDDER_PER_RAD * dr;
  const double cm = AIRFRAME_CM0 + AIRFRAME_CM_ALPHA_PER_RAD * alpha +
                    AIRFRAME_CM_Q_PER_RAD * qhat + AIRFRAME_CM_ELEVATOR_PER_RAD * de;
  const double cn = AIRFRAME_CN_BETA_PER_RAD * beta + AIRFRAME_CN_P_PER_RAD * phat +
                    AIRFRAME_CN_R_PER_RAD * rhat + AIRFRAME_CN_AILERON_PER_RAD * da +
                    AIRFRAME_CN_RUDDER_PER_RAD * dr;
  const double s = AIRFRAME_WING_AREA_M2;
  const double lift = qbar * s * cl, drag = qbar * s * cd;
  const double thrust =
      cmd.throttle * AIRFRAME_MAX_THRUST_N * (1.0 - vt / AIRFRAME_ZERO_THRUST_SPEED_M_S);
  const Eigen::Vector3d force(-drag * std::cos(alpha) + lift * std::sin(alpha) + thrust,
                              qbar * s * cy, -drag * std::sin(alpha) - lift * std::cos(alpha));
  const Eigen::Vector3d moment(qbar * s * AIRFRAME_WING_SPAN_M * croll,
                               qbar * s * AIRFRAME_MEAN_CHORD_M * cm,
                               qbar * s * AIRFRAME_WING_SPAN_M * cn);
  const double mass_kg = AIRFRAME_MASS_KG * config_.mass_scale;
  const Eigen::Vector3d f = force / mass_kg;
  if (specific_force != nullptr) {
    *specific_force = f;
  }
  const Eigen::Vector3d g_body =
      r_nb.transpose() * Eigen::Vector3d(0.0, 0.0, AIRFRAME_GRAVITY_M_S2);
  const Eigen::Vector3d inertia =
      config_.mass_scale *
      Eigen::Vector3d(AIRFRAME_IXX_KG_M2, AIRFRAME_IYY_KG_M2, AIRFRAME_IZZ_KG_M2);
  const Eigen::Vector3d iw = inertia.cwiseProduct(w);
  const Eigen::Vector3d wdot = (moment - w.cross(iw)).cwiseQuotient(inertia);
  const double sf = std::sin(e.x()), cf = std::cos(e.x()), ct = std::cos(e.y()),
               tt = std::tan(e.y());
  State d;
  d.segment<3>(0) = r_nb * v;
  d.segment<3>(3) = f + g_body - w.cross(v);
  d.segment<3>(6) = wdot;
  d.segment<3>(9) = Eigen::Vector3d(w.x() + tt * (w.y() * sf + w.z() * cf), w.y() * cf - w.z() * sf,
                                    (w.y() * sf + w.z() * cf) / ct);
  return d;
}

void Sim::advance(const GncOutput &cmd_in, double dt_s) {
  if (on_ground_) {
    roll_on_ground(dt_s);
    return;
  }
  GncOutput cmd = cmd_in;
  // RK4 in sub-steps no longer than 5 ms: the short period of this airframe is about 1 s.
  const int n = std::max(1, static_cast<int>(std::ceil(dt_s / 0.005)));
  const double h = dt_s / n;
  for (int i = 0; i < n; ++i) {
    const State x = pack();
    const State k1 = derivatives(x, cmd, nullptr);
    const State k2 = derivatives(x + 0.5 * h * k1, cmd, nullptr);
    const State k3 = derivatives(x + 0.5 * h * k2, cmd, nullptr);
    const State k4 = derivatives(x + h * k3, cmd, nullptr);
    State next = x + h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    next(11) = std::atan2(std::sin(next(11)), std::cos(next(11)));
    unpack(next);
  }
  derivatives(pack(), cmd, &specific_force_mps2_);
}

void Sim::sense(GncInput &in) {
  const double k = config_.noise_scale;
  auto noise = [this, k](double sigma) { return k * sigma * unit_(rng_); };
  const Eigen::Matrix3d r_nb = body_to_ned(euler_);
  const Eigen::Vector3d v_ned = r_nb * vel_body_mps_;
  // The stack's flat earth about home (geo_wgs84.h): the test flies in WGS84 as the real sensor
  // reports it.
  GeoRef home{};
  geo_ref_init(&home, config_.home_lat_deg, config_.home_lon_deg, config_.home_alt_m);
  const double neu_m[3] = {pos_ned_m_.x(), pos_ned_m_.y(), -pos_ned_m_.z()};
  double lat_deg, lon_deg, alt_m;
  geo_from_neu_m(&home, neu_m, &lat_deg, &lon_deg, &alt_m);
  in.lat_deg = lat_deg + noise(2e-6);
  in.lon_deg = lon_deg + noise(2e-6);
  in.alt_m = alt_m + noise(0.3);
  in.vel_north_mps = v_ned.x() + noise(0.05);
  in.vel_east_mps = v_ned.y() + noise(0.05);
  in.vel_down_mps = v_ned.z() + noise(0.05);
  in.p_radps = rates_radps_.x() + noise(0.002);
  in.q_radps = rates_radps_.y() + noise(0.002);
  in.r_radps = rates_radps_.z() + noise(0.002);
  in.fx_mps2 = specific_force_mps2_.x() + noise(0.05);
  in.fy_mps2 = specific_force_mps2_.y() + noise(0.05);
  in.fz_mps2 = specific_force_mps2_.z() + noise(0.05);
  in.phi_rad = euler_.x() + noise(0.002);
  in.theta_rad = euler_.y() + noise(0.002);
  in.psi_rad = euler_.z() + noise(0.005);
  // The pitot reads the air going past it, on the ground too (a parked aircraft in a wind).
  in.airspeed_ftps = std::max(0.0, airspeed_ftps() + noise(0.3));
  in.home_valid = 1;
  in.home_lat_deg = config_.home_lat_deg;
  in.home_lon_deg = config_.home_lon_deg;
  in.home_alt_m = config_.home_alt_m;
}

}  // namespace airframe_sim
