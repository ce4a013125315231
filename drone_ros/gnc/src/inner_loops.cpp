#include "inner_loops.h"

#include <algorithm>

#include "gnc_aircraft.h"

namespace gnc {

Surfaces clamp_to_limits(const Surfaces &u, const SurfaceLimits &lim) {
  Surfaces c;
  c.elevator_rad = std::clamp(u.elevator_rad, -lim.elevator_pull_rad, lim.elevator_rad);
  c.aileron_rad = std::clamp(u.aileron_rad, -lim.aileron_rad, lim.aileron_rad);
  c.rudder_rad = std::clamp(u.rudder_rad, -lim.rudder_rad, lim.rudder_rad);
  c.throttle = std::clamp(u.throttle, lim.throttle_min, lim.throttle_max);
  return c;
}

void InnerLoops::reset() {
  int_vt_m_ = 0.0;
  int_theta_rad_s_ = 0.0;
  int_phi_rad_s_ = 0.0;
}

Surfaces InnerLoops::step(const LoopState &x, const LoopReference &ref, const Surfaces &trim,
                          const SurfaceLimits &lim, double dt_s, bool integrate) {
  const double e_vt = x.vt_mps - ref.vt_mps;
  const double e_theta = x.theta_rad - ref.theta_rad;
  const double e_phi = x.phi_rad - ref.phi_rad;
  const double lon[GNC_K_LON_COLS] = {
      e_vt, x.alpha_rad - GNC_TRIM_ALPHA_RAD, x.q_radps, e_theta, int_vt_m_, int_theta_rad_s_};
  const double lat[GNC_K_LAT_COLS] = {x.beta_rad, x.p_radps, x.r_radps - ref.r_radps, e_phi,
                                      int_phi_rad_s_};
  double u_lon[GNC_K_LON_ROWS] = {0.0, 0.0};
  double u_lat[GNC_K_LAT_ROWS] = {0.0, 0.0};
  for (int i = 0; i < GNC_K_LON_ROWS; ++i) {
    for (int j = 0; j < GNC_K_LON_COLS; ++j) {
      u_lon[i] -= GNC_K_LON[i][j] * lon[j];
    }
  }
  for (int i = 0; i < GNC_K_LAT_ROWS; ++i) {
    for (int j = 0; j < GNC_K_LAT_COLS; ++j) {
      u_lat[i] -= GNC_K_LAT[i][j] * lat[j];
    }
  }
  Surfaces u;
  u.elevator_rad = trim.elevator_rad + u_lon[0];
  u.throttle = trim.throttle + u_lon[1];
  u.aileron_rad = trim.aileron_rad + u_lat[0];
  u.rudder_rad = trim.rudder_rad + u_lat[1];
  const Surfaces c = clamp_to_limits(u, lim);
  // Conditional integration: a saturated loop stops integrating, so it cannot wind up.
  if (integrate) {
    if (c.elevator_rad == u.elevator_rad && c.throttle == u.throttle) {
      int_vt_m_ += e_vt * dt_s;
      int_theta_rad_s_ += e_theta * dt_s;
    }
    if (c.aileron_rad == u.aileron_rad && c.rudder_rad == u.rudder_rad) {
      int_phi_rad_s_ += e_phi * dt_s;
    }
  }
  return c;
}

}  // namespace gnc
