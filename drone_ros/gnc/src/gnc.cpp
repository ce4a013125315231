// The GNC entry points: input checking, unit conversion, and the estimator -> guidance ->
// inner-loop chain. All persistent state lives in one static instance, as in generated code.
#include "gnc.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <initializer_list>

#include "airdata_ekf.h"
#include "geo_wgs84.h"
#include "gnc_aircraft.h"
#include "guidance.h"
#include "inner_loops.h"

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegToRad = kPi / 180.0;
constexpr double kFtPerM = 1.0 / 0.3048;
constexpr double kMPerFt = 0.3048;
// Beyond what the sensors can report (VN-200: +/-2000 deg/s, +/-16 g, 515 m/s; a pitot on this
// airframe far beyond 1000 ft/s): a finite value out here is a corrupted message, not flight.
constexpr double kMaxRateRadps = 35.0;
constexpr double kMaxSpecificForceMps2 = 160.0;
constexpr double kMaxVelocityMps = 515.0;
constexpr double kMaxAirspeedFtps = 1000.0;
constexpr double kMaxAngleRad = 2.0 * 3.14159265358979323846;
constexpr double kMaxWaypointFt = 1.0e6;

struct Gnc {
  bool initialized = false;
  GncParams params{};
  gnc::SurfaceLimits limits{};
  gnc::AirdataEkf ekf;
  bool ekf_started = false;
  bool wing_borne = false;
  gnc::Guidance guidance;
  gnc::InnerLoops loops;
  GncOutput last{};
  uint32_t rejected = 0;
  // The attitude the loops are asked for (slewed towards the guidance's), rad.
  double phi_ref_rad = 0.0, theta_ref_rad = 0.0;
};

// Stall prevention, as ArduPlane's: the HA judges the stall by the load factor (IAS^2 cos(bank)
// against its switch speed squared, issue 22 F1), so a bank the speed cannot pay for is a
// takeover. The bank is limited so that V^2 cos(bank) stays at min_airspeed_cmd^2 (never below
// stall_prevention_min_bank_deg: the aircraft must still steer), and the airspeed demand rises with
// the square root of the load factor of the bank commanded. (HiL, moderate turbulence in a
// 16 ft/s headwind: the HP slowed to 49.5 ft/s in a 32 deg bank and lost the servos for STALL
// until latched.)
void stall_prevention(const GncParams &p, double vt_ftps, gnc::GuidanceCommand *gc) {
  const double floor_sq = p.min_airspeed_cmd_ftps * p.min_airspeed_cmd_ftps;
  const double cos_min = vt_ftps > 0.0 ? std::min(1.0, floor_sq / (vt_ftps * vt_ftps)) : 1.0;
  const double max_bank = std::max(p.stall_prevention_min_bank_deg * kDegToRad, std::acos(cos_min));
  gc->phi_cmd_rad = std::clamp(gc->phi_cmd_rad, -max_bank, max_bank);
  gc->vt_cmd_ftps =
      std::max(gc->vt_cmd_ftps, p.min_airspeed_cmd_ftps / std::sqrt(std::cos(gc->phi_cmd_rad)));
}

double slew(double from, double to, double max_step) {
  return from + std::clamp(to - from, -max_step, max_step);
}

Gnc g_gnc;

bool finite_all(const double *v, size_t n) {
  for (size_t i = 0; i < n; ++i) {
    if (!std::isfinite(v[i])) {
      return false;
    }
  }
  return true;
}

// A waypoint table is stored as columns (north, east, height, speed), each n long.
bool finite_columns(std::initializer_list<const double *> columns, size_t n) {
  for (const double *c : columns) {
    if (!finite_all(c, n)) return false;
  }
  return true;
}

bool input_finite(const GncInput &in) {
  const double scalars[] = {
      in.airspeed_ftps,   in.throttle_trim, in.elevator_trim_rad, in.aileron_trim_rad,
      in.rudder_trim_rad, in.lat_deg,       in.lon_deg,           in.alt_m,
      in.vel_north_mps,   in.vel_east_mps,  in.vel_down_mps,      in.p_radps,
      in.q_radps,         in.r_radps,       in.fx_mps2,           in.fy_mps2,
      in.fz_mps2,         in.phi_rad,       in.theta_rad,         in.psi_rad,
      in.home_lat_deg,    in.home_lon_deg,  in.home_alt_m};
  return finite_all(scalars, sizeof(scalars) / sizeof(scalars[0])) &&
         finite_columns({in.wp_north_ft, in.wp_east_ft, in.wp_height_ft, in.wp_velocity_ftps},
                        GNC_MAX_WAYPOINTS);
}

bool within(double v, double limit) { return v >= -limit && v <= limit; }

bool input_plausible(const GncInput &in) {
  bool ok = within(in.airspeed_ftps, kMaxAirspeedFtps) && within(in.lat_deg, 90.0) &&
            within(in.lon_deg, 180.0) && within(in.home_lat_deg, 90.0) &&
            within(in.home_lon_deg, 180.0) && within(in.vel_north_mps, kMaxVelocityMps) &&
            within(in.vel_east_mps, kMaxVelocityMps) && within(in.vel_down_mps, kMaxVelocityMps) &&
            within(in.p_radps, kMaxRateRadps) && within(in.q_radps, kMaxRateRadps) &&
            within(in.r_radps, kMaxRateRadps) && within(in.fx_mps2, kMaxSpecificForceMps2) &&
            within(in.fy_mps2, kMaxSpecificForceMps2) &&
            within(in.fz_mps2, kMaxSpecificForceMps2) && within(in.phi_rad, kMaxAngleRad) &&
            within(in.theta_rad, kMaxAngleRad) && within(in.psi_rad, kMaxAngleRad) &&
            within(in.alt_m - in.home_alt_m, 1.0e5) && within(in.throttle_trim, 1.0) &&
            within(in.elevator_trim_rad, kMaxAngleRad) &&
            within(in.aileron_trim_rad, kMaxAngleRad) && within(in.rudder_trim_rad, kMaxAngleRad);
  for (int i = 0; ok && i < GNC_MAX_WAYPOINTS; ++i) {
    ok = within(in.wp_north_ft[i], kMaxWaypointFt) && within(in.wp_east_ft[i], kMaxWaypointFt) &&
         within(in.wp_height_ft[i], kMaxWaypointFt) &&
         within(in.wp_velocity_ftps[i], kMaxAirspeedFtps);
  }
  return ok;
}

bool output_finite(const GncOutput &o) {
  const double v[] = {o.throttle,       o.elevator_rad,    o.aileron_rad,    o.rudder_rad,
                      o.vt_est_ftps,    o.alpha_est_rad,   o.beta_est_rad,   o.alpha_sigma_rad,
                      o.beta_sigma_rad, o.wind_north_ftps, o.wind_east_ftps, o.wind_up_ftps,
                      o.north_ft,       o.east_ft,         o.height_ft,      o.dist_to_waypoint_ft,
                      o.cross_track_ft, o.vt_cmd_ftps,     o.phi_cmd_rad,    o.theta_cmd_rad,
                      o.beta_cmd_rad,   o.eta_lat_rad,     o.eta_lon_rad,    o.delta_psi_rad,
                      o.n_op_ft,        o.e_op_ft,         o.h_op_ft};
  return finite_all(v, sizeof(v) / sizeof(v[0])) &&
         finite_columns({o.mw_north_ft, o.mw_east_ft, o.mw_height_ft, o.mw_velocity_ftps},
                        GNC_PREVIEW_WAYPOINTS);
}

bool params_valid(const GncParams &p) {
  const double v[] = {p.dt_s,
                      p.elevator_limit_deg,
                      p.elevator_pull_limit_deg,
                      p.aileron_limit_deg,
                      p.rudder_limit_deg,
                      p.throttle_min,
                      p.throttle_max,
                      p.stall_speed_ftps,
                      p.vt_trim_ftps,
                      p.alpha0_rad,
                      p.beta0_rad,
                      p.mpf_radius_ft,
                      p.max_allow_error_ft,
                      p.dist2b_ft,
                      p.kp_lon_rad_per_ft,
                      p.ki_lon_rad_per_ft_s,
                      p.max_bank_deg,
                      p.max_pitch_cmd_deg,
                      p.attitude_cmd_rate_deg_s,
                      p.min_airspeed_cmd_ftps,
                      p.stall_prevention_min_bank_deg,
                      p.airspeed_valid_min_ftps,
                      p.converged_sigma_deg,
                      p.airborne_agl_ft};
  if (!finite_all(v, sizeof(v) / sizeof(v[0]))) {
    return false;
  }
  return p.dt_s > 0.0 && p.dt_s <= 0.1 && p.elevator_limit_deg > 0.0 &&
         p.elevator_pull_limit_deg > 0.0 && p.elevator_pull_limit_deg <= p.elevator_limit_deg &&
         p.aileron_limit_deg > 0.0 && p.rudder_limit_deg > 0.0 && p.throttle_min >= 0.0 &&
         p.throttle_max <= 1.0 && p.throttle_min < p.throttle_max && p.stall_speed_ftps > 0.0 &&
         p.vt_trim_ftps > p.stall_speed_ftps && p.mpf_radius_ft > 0.0 &&
         p.max_allow_error_ft > 0.0 && p.dist2b_ft > 0.0 && p.kp_lon_rad_per_ft >= 0.0 &&
         p.ki_lon_rad_per_ft_s >= 0.0 && p.max_bank_deg > 0.0 && p.max_bank_deg < 90.0 &&
         p.max_pitch_cmd_deg > 0.0 && p.max_pitch_cmd_deg < 90.0 &&
         p.attitude_cmd_rate_deg_s > 0.0 && p.min_airspeed_cmd_ftps > p.stall_speed_ftps &&
         p.stall_prevention_min_bank_deg > 0.0 &&
         p.stall_prevention_min_bank_deg <= p.max_bank_deg && p.airspeed_valid_min_ftps > 0.0 &&
         p.airspeed_valid_min_ftps < p.stall_speed_ftps && p.converged_sigma_deg > 0.0 &&
         p.airborne_agl_ft >= 0.0 && (p.guidance_selection == 0 || p.guidance_selection == 1) &&
         (p.mpf_switch == 0 || p.mpf_switch == 1) && (p.path_select == 0 || p.path_select == 1) &&
         std::fabs(p.alpha0_rad) < kPi / 2.0 && std::fabs(p.beta0_rad) < kPi / 2.0;
}

// The wing carries the aircraft, so the lift and side-force models hold and tell alpha and beta:
// entered at or above the 1 g stall speed (below it the wing cannot carry the weight: the wheels
// do) once above the airborne height (limits.yaml airborne_agl_ft, the HA's own alt0; without a
// home, on the airspeed alone), so that a take-off roll past the stall speed is still on the
// wheels. With a home it is left only low and below the stall speed again (landed, rolling out):
// a pitot reading zero at 200 ft is a dropout (the HA sends 0 while its own state is lost), not
// a landing. Without a home, on the airspeed alone.
bool wing_borne(bool was, double airspeed_ftps, bool home, double height_ft, const GncParams &p) {
  const bool low = home && height_ft <= p.airborne_agl_ft;
  if (was) {
    return home ? !(low && airspeed_ftps < p.stall_speed_ftps)
                : airspeed_ftps >= p.airspeed_valid_min_ftps;
  }
  return !low && airspeed_ftps >= p.stall_speed_ftps;
}

// A neutral command, flagged invalid: what the GNC says when it has nothing to fly.
GncOutput neutral_output(double throttle_min) {
  GncOutput o;
  std::memset(&o, 0, sizeof(o));
  o.throttle = throttle_min;
  o.alpha_sigma_rad = kPi;
  o.beta_sigma_rad = kPi;
  o.guidance_mode = GNC_MODE_CIRCLE_HOME;
  return o;
}

}  // namespace

extern "C" int gnc_initialize(const GncParams *params) {
  g_gnc = Gnc{};
  g_gnc.last = neutral_output(0.0);
  if (params == nullptr || !params_valid(*params)) {
    return -1;
  }
  g_gnc.params = *params;
  g_gnc.limits = {params->elevator_limit_deg * kDegToRad,
                  params->elevator_pull_limit_deg * kDegToRad,
                  params->aileron_limit_deg * kDegToRad,
                  params->rudder_limit_deg * kDegToRad,
                  params->throttle_min,
                  params->throttle_max};
  g_gnc.last = neutral_output(params->throttle_min);
  g_gnc.guidance.reset(*params, GNC_TRIM_THETA_RAD);
  g_gnc.loops.reset();
  g_gnc.initialized = true;
  return 0;
}

extern "C" void gnc_terminate(void) { g_gnc.initialized = false; }

namespace {

// What the estimator measures this step. The surfaces actually deflected: the pilot's (captured
// as trims every step while the pilot flies) or our last command.
gnc::AirdataMeasurement measurement(const GncInput &in) {
  gnc::AirdataMeasurement m;
  m.vel_ned_mps = {in.vel_north_mps, in.vel_east_mps, in.vel_down_mps};
  m.rates_radps = {in.p_radps, in.q_radps, in.r_radps};
  m.specific_force_mps2 = {in.fx_mps2, in.fy_mps2, in.fz_mps2};
  m.euler_rad = {in.phi_rad, in.theta_rad, in.psi_rad};
  m.airspeed_mps = in.airspeed_ftps * kMPerFt;
  m.elevator_rad = in.piccic == 0 ? in.elevator_trim_rad : g_gnc.last.elevator_rad;
  m.rudder_rad = in.piccic == 0 ? in.rudder_trim_rad : g_gnc.last.rudder_rad;
  return m;
}

// Flat earth around home, as the original's GPS-to-local block, by the stack's one conversion
// (geo_wgs84.h, gnc.cmake links it): waypoints the operator places, the HA's safety region and
// this guidance agree on where a latitude/longitude is relative to home. A home the module
// refuses (an absurd height) is no home. Whether there is one.
bool locate(const GncInput &in, GncOutput *o) {
  GeoRef ref{};
  const bool home = in.home_valid != 0 &&
                    geo_ref_init(&ref, in.home_lat_deg, in.home_lon_deg, in.home_alt_m) != 0;
  if (home) {
    double neu_ft[3];
    geo_to_neu_ft(&ref, in.lat_deg, in.lon_deg, in.alt_m, neu_ft);
    o->north_ft = neu_ft[0];
    o->east_ft = neu_ft[1];
    o->height_ft = neu_ft[2];
  }
  return home;
}

// The air data: the filter started on its first step and stepped after, started over when its
// state breaks.
gnc::AirdataEstimate estimate(const gnc::AirdataMeasurement &m, GncOutput *o) {
  const GncParams &p = g_gnc.params;
  gnc::AirdataEstimate est;
  if (!g_gnc.ekf_started) {
    const gnc::AirdataEkf::Config cfg{p.airspeed_valid_min_ftps * kMPerFt,
                                      p.converged_sigma_deg * kDegToRad,
                                      p.stall_speed_ftps * kMPerFt};
    g_gnc.ekf.reset(cfg, m, p.alpha0_rad, p.beta0_rad);
    g_gnc.ekf_started = true;
    est = g_gnc.ekf.peek(m);
  } else {
    est = g_gnc.ekf.step(m, p.dt_s);
  }
  if (!std::isfinite(est.vt_mps) || !std::isfinite(est.alpha_rad) || !std::isfinite(est.beta_rad) ||
      !est.wind_ned_mps.allFinite()) {
    // Cannot happen with plausible inputs; if it does, start the filter over next step rather
    // than carry a broken state.
    g_gnc.ekf_started = false;
    est = gnc::AirdataEstimate{};
  }
  o->vt_est_ftps = est.vt_mps * kFtPerM;
  o->alpha_est_rad = est.alpha_rad;
  o->beta_est_rad = est.beta_rad;
  o->alpha_sigma_rad = est.alpha_sigma_rad;
  o->beta_sigma_rad = est.beta_sigma_rad;
  o->wind_north_ftps = est.wind_ned_mps.x() * kFtPerM;
  o->wind_east_ftps = est.wind_ned_mps.y() * kFtPerM;
  o->wind_up_ftps = -est.wind_ned_mps.z() * kFtPerM;
  o->estimator_converged = est.converged ? 1 : 0;
  return est;
}

// Guidance, stall prevention and the attitude references the loops follow; the guidance's
// figures and the next waypoints into the output.
gnc::GuidanceCommand guide(const GncInput &in, const gnc::AirdataEstimate &est, bool flying,
                           GncOutput *o) {
  const GncParams &p = g_gnc.params;
  const gnc::GuidanceState gs{
      o->north_ft, o->east_ft, o->height_ft, in.vel_north_mps * kFtPerM, in.vel_east_mps * kFtPerM,
      in.psi_rad};
  gnc::GuidanceCommand gc = g_gnc.guidance.step(in, gs, flying);
  if (est.converged) {
    stall_prevention(p, est.vt_mps * kFtPerM, &gc);
  }
  // While this command is not flown (the HA or the pilot flies, the loops not closed) the
  // reference is the attitude the aircraft has, so that a hand-back starts from it.
  if (flying && in.ha_in_control == 0) {
    const double step_rad = p.attitude_cmd_rate_deg_s * kDegToRad * p.dt_s;
    g_gnc.phi_ref_rad = slew(g_gnc.phi_ref_rad, gc.phi_cmd_rad, step_rad);
    g_gnc.theta_ref_rad = slew(g_gnc.theta_ref_rad, gc.theta_cmd_rad, step_rad);
  } else {
    g_gnc.phi_ref_rad = in.phi_rad;
    g_gnc.theta_ref_rad = in.theta_rad;
  }
  o->guidance_mode = gc.mode;
  o->waypoint_index = gc.waypoint_index;
  o->dist_to_waypoint_ft = gc.dist_to_waypoint_ft;
  o->cross_track_ft = gc.cross_track_ft;
  o->vt_cmd_ftps = gc.vt_cmd_ftps;
  o->phi_cmd_rad = g_gnc.phi_ref_rad;
  o->theta_cmd_rad = g_gnc.theta_ref_rad;
  o->beta_cmd_rad = 0.0;  // coordinated flight
  o->eta_lat_rad = gc.eta_lat_rad;
  o->eta_lon_rad = gc.eta_lon_rad;
  o->delta_psi_rad = gc.delta_psi_rad;
  o->n_op_ft = gc.n_op_ft;
  o->e_op_ft = gc.e_op_ft;
  o->h_op_ft = gc.h_op_ft;
  const int32_t count =
      in.wp_count < 0 ? 0 : (in.wp_count > GNC_MAX_WAYPOINTS ? GNC_MAX_WAYPOINTS : in.wp_count);
  for (int32_t k = 0; k < GNC_PREVIEW_WAYPOINTS && count > 0; ++k) {
    const int32_t w = (gc.waypoint_index + k) % count;
    o->mw_north_ft[k] = in.wp_north_ft[w];
    o->mw_east_ft[k] = in.wp_east_ft[w];
    o->mw_height_ft[k] = in.wp_height_ft[w];
    o->mw_velocity_ftps[k] = in.wp_velocity_ftps[w];
  }
  return gc;
}

// The inner loops on the air data, or, without it, the trims held.
gnc::Surfaces fly_loops(const GncInput &in, const gnc::AirdataEstimate &est,
                        const gnc::GuidanceCommand &gc, bool flying) {
  const gnc::Surfaces trim{in.elevator_trim_rad, in.aileron_trim_rad, in.rudder_trim_rad,
                           in.throttle_trim};
  if (!est.converged) {
    // No air data to close the loops on: hold the trims, forget the integrators.
    g_gnc.loops.reset();
    return gnc::clamp_to_limits(trim, g_gnc.limits);
  }
  const gnc::LoopState x{est.vt_mps, est.alpha_rad, est.beta_rad, in.p_radps,
                         in.q_radps, in.r_radps,    in.phi_rad,   in.theta_rad};
  // est.converged implies vt >= airspeed_valid_min > 0.
  const double vt_cmd_mps = gc.vt_cmd_ftps * kMPerFt;
  const gnc::LoopReference ref{vt_cmd_mps, g_gnc.theta_ref_rad, g_gnc.phi_ref_rad,
                               AIRFRAME_GRAVITY_M_S2 / est.vt_mps * std::sin(g_gnc.phi_ref_rad)};
  return g_gnc.loops.step(x, ref, trim, g_gnc.limits, g_gnc.params.dt_s, flying);
}

}  // namespace

extern "C" void gnc_step(const GncInput *in, GncOutput *out) {
  if (out == nullptr) {
    return;
  }
  if (!g_gnc.initialized || in == nullptr) {
    *out = neutral_output(g_gnc.initialized ? g_gnc.params.throttle_min : 0.0);
    return;
  }
  if (!input_finite(*in) || !input_plausible(*in)) {
    // Dropped and counted; the last finite command is repeated, flagged invalid.
    ++g_gnc.rejected;
    *out = g_gnc.last;
    out->command_valid = 0;
    out->inputs_finite = 0;
    out->estimator_converged = 0;
    out->rejected_inputs = g_gnc.rejected;
    return;
  }
  const GncParams &p = g_gnc.params;
  GncOutput o = neutral_output(p.throttle_min);
  o.inputs_finite = 1;
  o.rejected_inputs = g_gnc.rejected;

  gnc::AirdataMeasurement m = measurement(*in);
  const bool home = locate(*in, &o);
  g_gnc.wing_borne = wing_borne(g_gnc.wing_borne, in->airspeed_ftps, home, o.height_ft, p);
  m.wing_borne = g_gnc.wing_borne;
  const gnc::AirdataEstimate est = estimate(m, &o);
  const bool flying = in->piccic == 1 && est.converged && home;
  const gnc::GuidanceCommand gc = guide(*in, est, flying, &o);
  const gnc::Surfaces u = fly_loops(*in, est, gc, flying);
  o.elevator_rad = u.elevator_rad;
  o.aileron_rad = u.aileron_rad;
  o.rudder_rad = u.rudder_rad;
  o.throttle = u.throttle;
  o.command_valid = (est.converged && home) ? 1 : 0;

  if (!output_finite(o)) {
    // Cannot happen with finite inputs and validated parameters; if it ever does, say so.
    o = neutral_output(p.throttle_min);
    o.inputs_finite = 1;
    o.rejected_inputs = g_gnc.rejected;
  }
  g_gnc.last = o;
  *out = o;
}
