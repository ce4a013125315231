// LQR inner loops around the generated gains (gnc_aircraft.h, from the aircraft's gains.yaml):
// longitudinal (airspeed and pitch tracking with elevator and throttle) and lateral-directional
// (roll tracking and sideslip suppression with aileron and rudder), each with integral action on
// its tracked errors.
#ifndef GNC_INNER_LOOPS_H
#define GNC_INNER_LOOPS_H

namespace gnc {

struct LoopState {
  double vt_mps, alpha_rad, beta_rad;
  double p_radps, q_radps, r_radps;
  double phi_rad, theta_rad;
};

struct LoopReference {
  double vt_mps, theta_rad, phi_rad;
  double r_radps;  // yaw rate of the coordinated turn at phi_rad, so the loop does not fight it
};

// Control surfaces in rad, throttle 0..1; also used for trims and limits.
struct Surfaces {
  double elevator_rad = 0.0, aileron_rad = 0.0, rudder_rad = 0.0, throttle = 0.0;
};

// Symmetric but for the elevator: trailing edge down positive, so a pull is negative, and the
// loops pull no further than the HA accepts airborne (limits.yaml elevator_pull_limit_deg).
struct SurfaceLimits {
  double elevator_rad, elevator_pull_rad, aileron_rad, rudder_rad, throttle_min, throttle_max;
};

Surfaces clamp_to_limits(const Surfaces &u, const SurfaceLimits &lim);

class InnerLoops {
 public:
  void reset();
  // integrate: false while the output is not flown (pilot in command), so integrators hold.
  Surfaces step(const LoopState &x, const LoopReference &ref, const Surfaces &trim,
                const SurfaceLimits &lim, double dt_s, bool integrate);

 private:
  double int_vt_m_ = 0.0;
  double int_theta_rad_s_ = 0.0;
  double int_phi_rad_s_ = 0.0;
};

}  // namespace gnc

#endif
