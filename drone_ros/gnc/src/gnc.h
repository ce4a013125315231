/* The guidance, navigation and control law behind Simulink-Coder style entry points:
 * initialize / step / terminate over plain input, output and parameter structs. The boundary is
 * C so a lab can drop in its own generated controller; the inside is C++17 with Eigen.
 * Units are in the names; angles in rad unless _deg. One instance per process, as generated
 * code is (gnc_initialize() resets it: the HP restart). */
#ifndef GNC_H
#define GNC_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define GNC_MAX_WAYPOINTS 32
#define GNC_PREVIEW_WAYPOINTS 6

/* Guidance modes (GncOutput.guidance_mode). */
#define GNC_MODE_FLIGHT_PLAN 0 /* following the /way legs */
#define GNC_MODE_DIRECT 1      /* beyond max_allow_error: heading straight for the waypoint */
#define GNC_MODE_CIRCLE_HOME 2 /* return home / end of plan / no plan: circle home */

typedef struct {
  double dt_s; /* step period */
  /* limits.yaml */
  double elevator_limit_deg, aileron_limit_deg, rudder_limit_deg;
  /* the HA refuses a pull past this airborne (REASON_PULL): the loops saturate there */
  double elevator_pull_limit_deg;
  double throttle_min, throttle_max;
  double stall_speed_ftps;
  /* controller_param.yaml */
  double vt_trim_ftps;
  double alpha0_rad, beta0_rad; /* initial estimator guess */
  int32_t guidance_selection;   /* 0 flight plan, 1 return home */
  int32_t mpf_switch;           /* 1 moving point (L1) on legs, 0 direct to waypoint */
  double mpf_radius_ft;
  int32_t path_select; /* end of plan: 0 restart it, 1 circle home */
  double max_allow_error_ft;
  double dist2b_ft;
  double kp_lon_rad_per_ft, ki_lon_rad_per_ft_s;
  double max_bank_deg, max_pitch_cmd_deg;
  double attitude_cmd_rate_deg_s; /* fastest the bank and pitch commands move */
  double min_airspeed_cmd_ftps;
  double stall_prevention_min_bank_deg; /* stall prevention limits the bank no further */
  double airspeed_valid_min_ftps;
  double converged_sigma_deg;
  /* limits.yaml state/airborne_agl_ft (the HA's alt0): with a home, the estimator takes the wing
   * to carry the aircraft (lift and side force measure alpha and beta) only above this height */
  double airborne_agl_ft;
} GncParams;

typedef struct {
  /* HA computer (/pwm): pilot switch and pitot */
  uint8_t piccic;        /* 0 pilot in command, 1 computer */
  uint8_t ha_in_control; /* 1 while the HA flies its own command instead of this one */
  double airspeed_ftps;  /* true airspeed from the pitot */
  /* trims to fly around (captured from the RC by the node while the pilot flies) */
  double throttle_trim, elevator_trim_rad, aileron_trim_rad, rudder_trim_rad;
  /* INS (/gps_position, /gps_velocity, /imu_PQR_acceleration, /attitude) */
  double lat_deg, lon_deg, alt_m; /* WGS84 */
  double vel_north_mps, vel_east_mps, vel_down_mps;
  double p_radps, q_radps, r_radps;   /* body FRD */
  double fx_mps2, fy_mps2, fz_mps2;   /* specific force, body FRD (about -g on z at rest) */
  double phi_rad, theta_rad, psi_rad; /* 3-2-1 Euler, NED */
  /* home: origin of the /way local frame (latched by the node; survives HP restarts) */
  uint8_t home_valid;
  double home_lat_deg, home_lon_deg, home_alt_m;
  uint8_t home_cmd; /* 1 = return home commanded */
  /* flight plan (/way), local North-East-Up from home */
  int32_t wp_count;
  double wp_north_ft[GNC_MAX_WAYPOINTS];
  double wp_east_ft[GNC_MAX_WAYPOINTS];
  double wp_height_ft[GNC_MAX_WAYPOINTS];
  double wp_velocity_ftps[GNC_MAX_WAYPOINTS];
  uint32_t wp_revision; /* changes when a new plan arrives: guidance restarts at leg 0 */
} GncInput;

typedef struct {
  /* commands, always finite and inside the limits */
  double throttle;
  double elevator_rad, aileron_rad, rudder_rad;
  uint8_t command_valid;    /* 0: do not fly this (input not finite, air data undefined) */
  uint8_t inputs_finite;    /* 0: this step's input had a NaN/inf and was dropped */
  uint32_t rejected_inputs; /* count of dropped input steps since initialize */
  /* estimation */
  double vt_est_ftps, alpha_est_rad, beta_est_rad;
  double alpha_sigma_rad, beta_sigma_rad;
  double wind_north_ftps, wind_east_ftps, wind_up_ftps; /* velocity of the air mass */
  uint8_t estimator_converged;
  double north_ft, east_ft, height_ft; /* position from home */
  /* guidance */
  int32_t guidance_mode;
  int32_t waypoint_index;
  double dist_to_waypoint_ft;
  double cross_track_ft;
  double vt_cmd_ftps, phi_cmd_rad, theta_cmd_rad, beta_cmd_rad;
  double eta_lat_rad, eta_lon_rad, delta_psi_rad;
  double n_op_ft, e_op_ft, h_op_ft; /* moving point */
  double mw_north_ft[GNC_PREVIEW_WAYPOINTS];
  double mw_east_ft[GNC_PREVIEW_WAYPOINTS];
  double mw_height_ft[GNC_PREVIEW_WAYPOINTS];
  double mw_velocity_ftps[GNC_PREVIEW_WAYPOINTS];
} GncOutput;

/* Returns 0 on success, -1 if a parameter is out of range (then the GNC stays uninitialized and
 * every step returns a neutral command flagged invalid). */
int gnc_initialize(const GncParams *params);
void gnc_step(const GncInput *in, GncOutput *out);
void gnc_terminate(void);

#ifdef __cplusplus
}
#endif

#endif /* GNC_H */
