#include "guidance.h"

#include <algorithm>
#include <cmath>

namespace gnc {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegToRad = kPi / 180.0;
constexpr double kGravityFtps2 = 32.1740486;

double wrap_pi(double a) { return std::atan2(std::sin(a), std::cos(a)); }

}  // namespace

void Guidance::reset(const GncParams &params, double theta_trim_rad) {
  params_ = params;
  theta_trim_rad_ = theta_trim_rad;
  have_plan_ = false;
  plan_done_ = false;
  plan_revision_ = 0;
  index_ = 0;
  circling_ = false;
  circle_height_ft_ = 0.0;
  alt_integral_ft_s_ = 0.0;
}

int32_t Guidance::next_index(int32_t index, int32_t count) const {
  if (index + 1 < count) {
    return index + 1;
  }
  return params_.path_select == 0 ? 0 : -1;  // -1: the plan ends here
}

void Guidance::start_leg(const GncInput &in, const GuidanceState &s, int32_t index,
                         bool from_here) {
  if (from_here) {
    leg_start_n_ft_ = s.north_ft;
    leg_start_e_ft_ = s.east_ft;
    leg_start_h_ft_ = s.height_ft;
  } else {
    leg_start_n_ft_ = in.wp_north_ft[index_];
    leg_start_e_ft_ = in.wp_east_ft[index_];
    leg_start_h_ft_ = in.wp_height_ft[index_];
  }
  index_ = index;
}

double Guidance::lateral_accel_cmd(const GuidanceState &s, double n_op, double e_op,
                                   GuidanceCommand &c) const {
  // L1 law: a = 2 V^2 / L1 * sin(eta), eta the angle from the ground track to the moving point.
  const double vg2 = s.vel_north_ftps * s.vel_north_ftps + s.vel_east_ftps * s.vel_east_ftps;
  const double vmin = params_.airspeed_valid_min_ftps;
  // Standing still the track is undefined: use the heading instead.
  const double track =
      vg2 >= vmin * vmin ? std::atan2(s.vel_east_ftps, s.vel_north_ftps) : s.psi_rad;
  const double bearing = std::atan2(e_op - s.east_ft, n_op - s.north_ft);
  const double eta = wrap_pi(bearing - track);
  c.eta_lat_rad = eta;
  const double sin_eta = std::fabs(eta) >= kPi / 2.0 ? (eta > 0.0 ? 1.0 : -1.0) : std::sin(eta);
  return 2.0 * vg2 / params_.mpf_radius_ft * sin_eta;
}

// Advances past every waypoint already reached; bounded so coincident waypoints cannot loop.
// The plan ends (and the circling starts) after its last waypoint with path_select 1.
void Guidance::advance_plan(const GncInput &in, const GuidanceState &s, int32_t count,
                            GuidanceCommand &c) {
  for (int32_t hop = 0; hop <= count && !plan_done_; ++hop) {
    const double wn = in.wp_north_ft[index_], we = in.wp_east_ft[index_];
    const double wh = in.wp_height_ft[index_];
    const double dn = wn - leg_start_n_ft_, de = we - leg_start_e_ft_;
    const double leg_ft = std::hypot(dn, de);
    const double rn = s.north_ft - leg_start_n_ft_, re = s.east_ft - leg_start_e_ft_;
    const double tn = leg_ft > 0.0 ? dn / leg_ft : 0.0, te = leg_ft > 0.0 ? de / leg_ft : 0.0;
    const double along_ft = rn * tn + re * te;
    c.cross_track_ft = tn * re - te * rn;  // positive right of the leg
    c.dist_to_waypoint_ft = std::hypot(wn - s.north_ft, we - s.east_ft);
    // Past the bisector of the corner the next leg is the nearer one: switch there, so the
    // turn is flown by the corner, not after overshooting it.
    bool past_bisector = false;
    const int32_t after = next_index(index_, count);
    if (after >= 0 && leg_ft > 0.0) {
      const double nn = in.wp_north_ft[after] - wn, ne = in.wp_east_ft[after] - we;
      const double next_ft = std::hypot(nn, ne);
      if (next_ft > 0.0) {
        const double bn = tn + nn / next_ft, be = te + ne / next_ft;
        past_bisector =
            (s.north_ft - wn) * bn + (s.east_ft - we) * be >= 0.0 && (bn != 0.0 || be != 0.0);
      }
    }
    const bool reached = c.dist_to_waypoint_ft <= params_.dist2b_ft ||
                         (leg_ft > 0.0 && along_ft >= leg_ft) || past_bisector;
    if (!reached) {
      break;
    }
    const int32_t next = next_index(index_, count);
    if (next < 0) {
      plan_done_ = true;  // until a new plan arrives
      circling_ = true;
      circle_height_ft_ = wh;
    } else {
      start_leg(in, s, next, false);  // the new leg starts at the waypoint just reached
    }
  }
}

// The moving point on the leg (L1 path following), or the waypoint itself when off the track.
void Guidance::follow_leg(const GncInput &in, const GuidanceState &s, int32_t count,
                          GuidanceCommand &c) {
  circling_ = false;
  const double wn = in.wp_north_ft[index_], we = in.wp_east_ft[index_],
               wh = in.wp_height_ft[index_];
  const double dn = wn - leg_start_n_ft_, de = we - leg_start_e_ft_;
  const double leg_ft = std::hypot(dn, de);
  const double tn = leg_ft > 0.0 ? dn / leg_ft : 0.0, te = leg_ft > 0.0 ? de / leg_ft : 0.0;
  const double along_ft = (s.north_ft - leg_start_n_ft_) * tn + (s.east_ft - leg_start_e_ft_) * te;
  const bool on_track = params_.mpf_switch == 1 && leg_ft > 0.0 &&
                        std::fabs(c.cross_track_ft) <= params_.max_allow_error_ft;
  if (on_track) {
    c.mode = GNC_MODE_FLIGHT_PLAN;
    const double r = params_.mpf_radius_ft;
    const double xt = c.cross_track_ft;
    const double ahead_ft = xt * xt < r * r ? std::sqrt(r * r - xt * xt) : 0.0;
    const double s_op = along_ft + ahead_ft;
    const double frac = std::clamp(s_op / leg_ft, 0.0, 1.0);
    c.n_op_ft = leg_start_n_ft_ + frac * dn;
    c.e_op_ft = leg_start_e_ft_ + frac * de;
    c.h_op_ft = leg_start_h_ft_ + frac * (wh - leg_start_h_ft_);
    // Past the corner the moving point runs on along the next leg, so the turn starts early.
    const int32_t after = next_index(index_, count);
    if (s_op > leg_ft && after >= 0) {
      const double nn = in.wp_north_ft[after] - wn, ne = in.wp_east_ft[after] - we;
      const double next_ft = std::hypot(nn, ne);
      if (next_ft > 0.0) {
        const double beyond = std::min(s_op - leg_ft, next_ft);
        c.n_op_ft = wn + beyond * nn / next_ft;
        c.e_op_ft = we + beyond * ne / next_ft;
        c.h_op_ft = wh + beyond / next_ft * (in.wp_height_ft[after] - wh);
      }
    }
  } else {
    c.mode = GNC_MODE_DIRECT;
    c.n_op_ft = wn;
    c.e_op_ft = we;
    c.h_op_ft = wh;
  }
  c.delta_psi_rad = wrap_pi(std::atan2(de, dn) - s.psi_rad);
  if (in.wp_velocity_ftps[index_] > 0.0) {
    c.vt_cmd_ftps = in.wp_velocity_ftps[index_];
  }
}

// Circle home, clockwise, radius mpf_radius, the moving point one radian ahead.
void Guidance::circle_home(const GuidanceState &s, GuidanceCommand &c) {
  c.mode = GNC_MODE_CIRCLE_HOME;
  if (!circling_) {
    circling_ = true;
    circle_height_ft_ = s.height_ft;
  }
  const double r = params_.mpf_radius_ft;
  const double bearing = std::atan2(s.east_ft, s.north_ft);
  c.n_op_ft = r * std::cos(bearing + 1.0);
  c.e_op_ft = r * std::sin(bearing + 1.0);
  c.h_op_ft = circle_height_ft_;
  c.dist_to_waypoint_ft = std::hypot(s.north_ft, s.east_ft);
  c.cross_track_ft = c.dist_to_waypoint_ft - r;
  c.delta_psi_rad = wrap_pi(bearing + kPi / 2.0 - s.psi_rad);
}

// Altitude: PI on the height error to the moving point gives the pitch command.
void Guidance::altitude_cmd(const GuidanceState &s, bool integrate, GuidanceCommand &c) {
  const double max_pitch = params_.max_pitch_cmd_deg * kDegToRad;
  const double err_ft = c.h_op_ft - s.height_ft;
  c.eta_lon_rad = std::atan2(err_ft, params_.mpf_radius_ft);
  const double unsat = theta_trim_rad_ + params_.kp_lon_rad_per_ft * err_ft +
                       params_.ki_lon_rad_per_ft_s * alt_integral_ft_s_;
  c.theta_cmd_rad = std::clamp(unsat, -max_pitch, max_pitch);
  // Conditional integration: only while unsaturated or while the error unwinds the saturation.
  const bool unwinding =
      (unsat > max_pitch && err_ft < 0.0) || (unsat < -max_pitch && err_ft > 0.0);
  if (integrate && (unsat == c.theta_cmd_rad || unwinding)) {
    alt_integral_ft_s_ += err_ft * params_.dt_s;
  }
}

GuidanceCommand Guidance::step(const GncInput &in, const GuidanceState &s, bool integrate) {
  GuidanceCommand c;
  const int32_t count = std::clamp<int32_t>(in.wp_count, 0, GNC_MAX_WAYPOINTS);
  const bool fly_plan = params_.guidance_selection == 0 && in.home_cmd == 0 && count > 0;

  if (fly_plan && (!have_plan_ || in.wp_revision != plan_revision_)) {
    // A new plan: first leg from where we are to waypoint 0.
    have_plan_ = true;
    plan_revision_ = in.wp_revision;
    plan_done_ = false;
    start_leg(in, s, 0, true);
  }
  if (index_ >= count) {
    index_ = 0;
  }
  c.vt_cmd_ftps = params_.vt_trim_ftps;
  if (fly_plan && !plan_done_) {
    advance_plan(in, s, count, c);
  }
  if (fly_plan && !plan_done_) {
    follow_leg(in, s, count, c);
  } else {
    circle_home(s, c);
  }
  c.waypoint_index = index_;
  c.vt_cmd_ftps = std::max(c.vt_cmd_ftps, params_.min_airspeed_cmd_ftps);

  const double max_bank = params_.max_bank_deg * kDegToRad;
  const double a_lat = lateral_accel_cmd(s, c.n_op_ft, c.e_op_ft, c);
  c.phi_cmd_rad = std::clamp(std::atan(a_lat / kGravityFtps2), -max_bank, max_bank);
  altitude_cmd(s, integrate, c);
  return c;
}

}  // namespace gnc
