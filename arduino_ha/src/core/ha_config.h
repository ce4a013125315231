/* Per-aircraft configuration of the HA core. Never filled by hand: tools/gen_aircraft_config.py
 * turns aircraft/<name>/limits.yaml into a const initializer (src/generated/aircraft_config.h),
 * so no limit is a literal in the core. Times are converted to integer microseconds by the
 * generator, so the core never converts a float to an integer time. */
#ifndef HA_CONFIG_H
#define HA_CONFIG_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* State vector x of the safety region S_x (x - x0) <= 1, in this order. */
enum {
  HA_X_ALPHA_DEG = 0,
  HA_X_BETA_DEG = 1,
  HA_X_ROLL_DEG = 2,
  HA_X_PITCH_DEG = 3,
  HA_X_P_DEG_S = 4,
  HA_X_Q_DEG_S = 5,
  HA_X_R_DEG_S = 6,
  HA_X_ALT_AGL_FT = 7,
  HA_X_DIM = 8
};

/* Actuator vector u of the actuator region S_u (u - u0) <= 1, in this order. */
enum {
  HA_U_ELEVATOR_DEG = 0,
  HA_U_AILERON_DEG = 1,
  HA_U_RUDDER_DEG = 2,
  HA_U_THROTTLE = 3,
  HA_U_DIM = 4
};

#define HA_SX_MAX_ROWS 20
#define HA_SU_MAX_ROWS 10
/* Nonzero coefficients a region may hold (a box has one a row; the thesis's polytope more). */
#define HA_SX_MAX_TERMS 64
#define HA_SU_MAX_TERMS 24

/* A nonzero coefficient of a region's row, S[row][col]: only these are stored, so that no zero
 * is multiplied or even looked at per period (on the Due the scan of the dense 15 x 8 and 8 x 4
 * matrices cost some 1,300 instructions a step). */
typedef struct {
  uint8_t col;
  float coef;
} HaRegionTerm;
/* Upper bound on max_restarts (the restart history is a fixed array). */
#define HA_MAX_RESTARTS_CAP 16

typedef struct {
  const char *aircraft;

  /* Safety regions: row i holds when sum_j S[i][j] * (v[j] - v0[j]) <= 1, S by rows of nonzero
   * terms: row i's are sx[sx_row_end[i - 1] .. sx_row_end[i] - 1] (from sx[0] for row 0). */
  uint32_t sx_rows;
  uint8_t sx_row_end[HA_SX_MAX_ROWS];
  HaRegionTerm sx[HA_SX_MAX_TERMS];
  float x0[HA_X_DIM];
  uint32_t su_rows;
  uint8_t su_row_end[HA_SU_MAX_ROWS];
  HaRegionTerm su[HA_SU_MAX_TERMS];
  float u0[HA_U_DIM];
  float inner_region_fraction; /* switch back only while max(S_x (x - x0)) <= this */
  /* ... and, airborne, only above this airspeed (stall x handback_stall_multiple, derived by the
   * generator): airspeed hovering at stall cannot cycle the HP and the HA. */
  float handback_airspeed_ftps;
  /* Switching happens on an inset, not on the edges (derived by the generator): above
   * max(S_x (x - x0)) = switch_region_fraction, above ceiling_switch_agl_ft, and, airborne, at or
   * below stall_switch_airspeed_ftps. The HA's sensors err and lag and its controller needs room
   * to turn the aircraft round inside S_x. */
  float switch_region_fraction;
  float ceiling_switch_agl_ft;
  float stall_switch_airspeed_ftps;

  /* Actuators (the box S_u is built from; the final saturation uses it directly). */
  float elevator_limit_deg;
  float aileron_limit_deg;
  float rudder_limit_deg;
  float throttle_min;
  float throttle_max;
  float surface_rate_limit_deg_per_s;
  float surface_release_rate_deg_per_s; /* a pull eased towards neutral (ha_surfaces.c) */
  /* Airborne, an HP elevator more nose-up than this (trailing edge up, elevator_deg below its
   * negative) trims the wing far past its stall: unsafe output (ha_checks.c). */
  float elevator_pull_limit_deg;
  float throttle_rate_limit_per_s;

  /* State checks. */
  float alpha_limit_deg; /* the HP's estimate past this: a diverged estimator */
  float stall_alpha_deg; /* the wing's stall angle of attack (airframe.yaml): the HA's own sign */
  float beta_limit_deg;
  float stall_speed_ftps;
  float ceiling_agl_ft;
  float airborne_agl_ft;      /* one signal of flight among several (ha_core.c: airborne latch) */
  uint32_t landed_confirm_us; /* a landing evident this long clears the airborne latch */
  float max_airspeed_ftps;    /* a reading above this is a broken sensor, not a fast aircraft */
  /* A reading more than this below the INS's groundspeed is a lying pitot, not a stall. */
  float max_wind_ftps;
  uint32_t state_timeout_us; /* attitude/position older than this is not trusted */
  /* A failed pitot read holds the last good one this long: a glitch is not a dead sensor. */
  uint32_t airspeed_timeout_us;

  /* Decision logic. */
  uint32_t period_us;
  uint32_t late_periods_tolerated;
  uint32_t no_command_timeout_us;
  uint32_t stable_window_us;
  uint32_t max_restarts;
  uint32_t restart_window_us;
  uint32_t hp_reset_pulse_us;
  /* From releasing the reset line to the HP's first valid command; past it the HP is reset
   * again (counting towards max_restarts), and at the cap the HA latches. */
  uint32_t hp_boot_timeout_us;

  /* RC receiver and servo pulse calibration: [min, max] maps linearly onto [-limit, +limit]
   * (throttle onto [throttle_min, throttle_max]). */
  uint32_t rc_pulse_min_us;
  uint32_t rc_pulse_max_us;
  uint32_t pic_threshold_us; /* PIC channel pulse >= this: pilot in command */
  uint32_t servo_pulse_min_us;
  uint32_t servo_pulse_max_us;
  /* The same mapping's slopes per microsecond above rc_pulse_min_us, derived by the generator:
   * a division per channel costs ~150 soft-float instructions on the Due. */
  float rc_elevator_deg_per_us;
  float rc_aileron_deg_per_us;
  float rc_rudder_deg_per_us;
  float rc_throttle_per_us;

  /* Safety controller (cascaded PID). */
  float sc_bank_limit_deg;
  float sc_circle_radius_ft;
  float sc_circle_direction; /* +1 clockwise seen from above (right turns), -1 counter-clockwise */
  /* Bank of a steady turn of sc_circle_radius_ft at the target airspeed, derived by the generator:
   * an atanf per period costs ~1,500 soft-float instructions on the Due. */
  float sc_circle_bank_ff_deg;
  float sc_radial_gain_deg_per_ft;
  float sc_radial_correction_max_deg;
  float sc_heading_to_bank_gain;
  float sc_roll_kp, sc_roll_ki, sc_roll_kd; /* aileron deg per deg, per deg*s, per deg/s */
  float sc_pitch_kp, sc_pitch_ki, sc_pitch_kd;
  float sc_yaw_damper_gain; /* rudder deg per deg/s of R */
  float sc_alt_min_ft;
  float sc_alt_max_ft;
  float sc_alt_to_pitch_gain_deg_per_ft;
  float sc_pitch_cmd_limit_deg;
  float sc_pitch_error_max_deg; /* the pitch loop's error is clamped to +/- this */
  /* The HA's own elevator stop, nose-up degrees: it trims the wing below its stall (generator). */
  float sc_elevator_pull_max_deg;
  /* Pitch and power without a speed: the nose no higher than this, the throttle trim plus this
   * per ft below the band's middle (derived: full at the band's floor). */
  float sc_power_pitch_deg;
  float sc_power_throttle_per_ft;
  /* Slow beats low: below stall_speed_ftps * sc_stall_margin the pitch loop lowers the nose at
   * every altitude; above it the nose may rise sc_speed_to_pitch_gain per ft/s of excess. */
  float sc_stall_margin;
  /* The pitch loop's lift guard: a load factor past lift_margin (IAS / V_stall)^2 (derived: the
   * margin / V_stall^2) pushes the nose down sc_lift_push_deg_per_g per g. */
  float sc_lift_margin_per_ias_sq;
  float sc_lift_push_deg_per_g;
  float sc_speed_to_pitch_gain_deg_per_ftps;
  float sc_cruise_margin; /* the throttle loop's target airspeed = stall_speed_ftps * this */
  float sc_throttle_trim;
  float sc_elevator_trim_deg; /* airframe.yaml's level trim at sc_target_ftps (generator) */
  float sc_throttle_kp_per_ftps;
  float sc_throttle_ki_per_ft;
  float sc_integrator_authority; /* integrator range as a fraction of the actuator half range */
  /* Without its own attitude the HA cannot close a loop: the integrators (what is left of the
   * HP's last surfaces) fade to zero, the trims, at this fraction of their authority per second,
   * derived by the generator as 1 / blind_fade_s. */
  float sc_blind_fade_per_s;

  /* Pre-flight surface self-test. */
  uint32_t self_test_step_us;
  float self_test_throttle_max;
  /* Parked, for the self-test: roll and pitch within, body rates within, ground speed below. */
  float self_test_max_tilt_deg;
  float self_test_max_rate_deg_s;
  float self_test_max_groundspeed_ftps;

  /* Air data (ha_airdata.c): the HA's own airspeed picture. The stall check compares squares:
   * IAS^2 cos(bank) against this, the stall switch speed squared (derived). */
  float stall_switch_airspeed_sq;
  float handback_airspeed_sq; /* handback_airspeed_ftps^2 (derived) */
  /* Once the wind is known, the pitot's true airspeed may differ this much from the INS's
   * velocity less the wind (gusts, sideslip, what the estimate is still off); before, by up to
   * max_wind_ftps from the speed over the ground. */
  float airspeed_tolerance_ftps;
  float max_wind_sq; /* max_wind_ftps^2 (derived): the wind estimate's bound */
  /* The wind estimate follows at 1 / wind_time_constant_s: this fraction per period (derived). */
  float wind_per_period;
  /* Learnt from a believed pitot this long the wind is known (derived: 3 x wind_time_constant_s,
   * 5% of the first error left); the pitot doubted wind_forget_us (1 x), it is unknown again. */
  uint32_t wind_known_us;
  uint32_t wind_forget_us;
  /* The same nonzero pitot reading this long is a stuck sensor (ha_airdata.c). */
  uint32_t pitot_stuck_us;
  /* The safety controller's circle in vectors (ha_safety_ctrl.c), derived: tan(correction) =
   * this x (d^2 - R^2) (radial_gain_deg_per_ft in rad / 2R: the same near the circle), bounded by
   * tan(radial_correction_max_deg); R^2. */
  float sc_radial_tan_per_ft2;
  float sc_radial_tan_max;
  float sc_circle_radius_sq_ft2;
  /* Derived by the generator, once instead of every period (ha_safety_ctrl.c): the throttle
   * loop's target (stall x cruise margin), the slowest speed the nose may rise at (stall x stall
   * margin), the band's middle, the throttle's half range and middle, the trim and the power's
   * room to full about them, the integrators' limits (authority x range) and fade per second. */
  float sc_target_ftps, sc_speed_floor_ftps, sc_alt_mid_ft;
  float sc_throttle_half, sc_throttle_mid, sc_throttle_trim_offset, sc_power_throttle_max;
  float sc_aileron_integ_limit, sc_elevator_integ_limit, sc_throttle_integ_limit;
  float sc_blind_fade_auth_per_s;
} HaAircraftConfig;

#ifdef __cplusplus
}
#endif

#endif /* HA_CONFIG_H */
