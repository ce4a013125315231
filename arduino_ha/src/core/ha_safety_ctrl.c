#include "ha_safety_ctrl.h"

#include "ha_num.h"
#include "ha_surfaces.h"

#define HA_DEG_PER_RAD 57.29578f

/* One PID channel with conditional-integration anti-windup and output saturation. When another
 * controller drives the surface, the integrator is back-calculated so pd + integ == applied, as
 * far as its authority allows; the core's rate limiter covers any remaining difference. */
static float pid(float *integ, float pd, float integ_step, float limit, float integ_limit,
                 int in_control, float applied) {
  if (!in_control) {
    *integ = ha_clampf(applied - pd, -integ_limit, integ_limit);
  } else {
    const float candidate = *integ + integ_step;
    const float unsat = pd + candidate;
    /* Integrate only while it does not push further into saturation (no windup). Compared on
     * the bits (ha_greater): a float compare is a library call of some 35 instructions. */
    if (!((ha_greater(unsat, limit) && ha_greater(integ_step, 0.0f)) ||
          (ha_greater(-limit, unsat) && ha_greater(0.0f, integ_step)))) {
      *integ = ha_clampf(candidate, -integ_limit, integ_limit);
    }
  }
  return ha_clampf(pd + *integ, -limit, limit);
}

static float toward_zero(float v, float step) {
  if (v > step) {
    return v - step;
  }
  return v < -step ? v + step : 0.0f;
}

/* Outer lateral loop: the bank that flies the circle around home, in vectors (an atan2f, a sqrtf
 * and a floorf cost some 2,500 soft-float instructions per period on the Due). The course is the
 * circle's tangent t = dir (-e, n) turned inwards by the correction, c = t - tan(corr) (n, e),
 * with tan(corr) = k (d^2 - R^2): k (d - R) 2R near the circle (the radial gain), more beyond,
 * bounded by tan(radial_correction_max). The heading error is the angle from the heading's unit
 * vector to c, atan(cross / dot) within 45 deg (a polynomial within 0.3 deg); beyond, +/-90 deg,
 * past which the bank saturates anyway. */
static float bank_command_deg(const HaAircraftConfig *cfg, const HaStateView *s) {
  const float dir = cfg->sc_circle_direction;
  const float n = s->north_ft;
  const float e = s->east_ft;
  float tan_corr, course_n, course_e, cross, dot, err_deg, bank_deg, limit_deg;
  if (!s->position_ok) {
    return 0.0f; /* without a position: wings level */
  }
  /* Finite: north and east are clamped to +/-1e6 ft by ha_state_view. */
  tan_corr = ha_clampf(cfg->sc_radial_tan_per_ft2 * (n * n + e * e - cfg->sc_circle_radius_sq_ft2),
                       -cfg->sc_radial_tan_max, cfg->sc_radial_tan_max);
  /* dir is +/-1: a sign, not a multiplication */
  course_n = (ha_greater(dir, 0.0f) ? -e : e) - tan_corr * n;
  course_e = (ha_greater(dir, 0.0f) ? n : -n) - tan_corr * e;
  cross = s->heading_north * course_e - s->heading_east * course_n;
  dot = s->heading_north * course_n + s->heading_east * course_e;
  /* dot > 1 ft^2 as a float compare, so EVA sees the division bounded; within a foot of home
   * any course will do. */
  if (dot > 1.0f && !ha_greater(cross, dot) && !ha_greater(-cross, dot)) {
    const float x = ha_clampf(cross / dot, -1.0f, 1.0f);
    err_deg = HA_DEG_PER_RAD * x * (0.7853982f + 0.273f * (1.0f - (ha_greater(0.0f, x) ? -x : x)));
  } else {
    err_deg = ha_greater(0.0f, cross) ? -90.0f : 90.0f;
  }
  /* Feed-forward: the bank of a steady turn of this radius at the target speed. */
  bank_deg = dir * cfg->sc_circle_bank_ff_deg + cfg->sc_heading_to_bank_gain * err_deg;
  /* Below the band, height beats the circle: no more bank than the circle's own, whose load the
   * power pays for; the circle is joined wider (HiL campaign seed 27 #4: 25 deg held for 20 s far
   * outside the circle sank the aircraft from 193 to 35 ft at 59 ft/s). */
  limit_deg = (s->altitude_ok && ha_greater(cfg->sc_alt_min_ft, s->x[HA_X_ALT_AGL_FT]))
                  ? cfg->sc_circle_bank_ff_deg
                  : cfg->sc_bank_limit_deg;
  return ha_clampf(bank_deg, -limit_deg, limit_deg); /* finite */
}

/* Outer longitudinal loop: the altitude band, but slow beats low. The nose may rise only as far
 * as the airspeed above stall x stall_margin pays for (speed_to_pitch_gain per ft/s); below that
 * speed the allowance is negative, so the nose goes down at every altitude, however low. The
 * altitude term can always lower the nose (above the band). The speed is the pitot's, or the
 * INS's less a known wind (ha_airdata.c). With neither, pitch and power, as a pilot flies with
 * unreliable airspeed: the nose no higher than the attitude that, at throttle_trim, flies the
 * cruise speed whatever the wind (and the check reports the HA lacking state). */
static float pitch_command_deg(const HaAircraftConfig *cfg, const HaStateView *s) {
  float pitch_deg = 0.0f;
  if (s->altitude_ok) {
    pitch_deg = cfg->sc_alt_to_pitch_gain_deg_per_ft * (cfg->sc_alt_mid_ft - s->x[HA_X_ALT_AGL_FT]);
  }
  const float allowed_deg = s->speed_known ? cfg->sc_speed_to_pitch_gain_deg_per_ftps *
                                                 (s->ias_ftps - cfg->sc_speed_floor_ftps)
                                           : cfg->sc_power_pitch_deg;
  pitch_deg = allowed_deg < pitch_deg ? allowed_deg : pitch_deg;
  return ha_clampf(pitch_deg, -cfg->sc_pitch_cmd_limit_deg, cfg->sc_pitch_cmd_limit_deg);
}

/* The lift guard: how far (in g, > 0) the wing's load (the gyros' or the accelerometer's,
 * ha_airdata.c) is past what the speed allows at sc_lift_margin of the wing's maximum lift, n <=
 * margin (IAS / V_stall)^2; 0 inside it or without a speed and attitude. Judged on the load, not on
 * an angle of attack from pitch less flight path: that one reads a sideslip in a bank (a slipping
 * 50 deg bank at a true 4 deg read 16) and a downdraft as alpha, and pushed the HA into a 31 deg
 * dive (HiL). */
static float lift_excess_g(const HaAircraftConfig *cfg, const HaStateView *s) {
  if (s->speed_known && s->attitude_ok) {
    const float excess = s->lift_load_factor - cfg->sc_lift_margin_per_ias_sq * s->ias_sq;
    return ha_greater(excess, 0.0f) ? excess : 0.0f;
  }
  return 0.0f;
}

/* One period's proportional-derivative terms and integrator steps of the three loops. */
typedef struct {
  float roll_pd, roll_step, pitch_pd, pitch_step, thr_pd, thr_step;
} LoopTerms;

/* The roll and pitch loops' terms, on an attitude. */
static void attitude_terms(const HaAircraftConfig *cfg, const HaStateView *s, float dt_s,
                           LoopTerms *t) {
  const float roll_err = bank_command_deg(cfg, s) - s->x[HA_X_ROLL_DEG];
  /* The error is bounded: a pitch target far from the nose (a dive it inherited, the speed's
   * source switching from a doubted pitot to the INS) is flown towards at a bounded pull, not
   * with the elevator at its stop (HiL pitot reading low: 38 deg of error at 75 ft/s, full up
   * elevator, 3.4 g and the wing stalled in the pull-out). Both terms are clamped: finite. */
  /* A stall is flown out as a pilot does, whatever the height asks: the nose to the pitch
   * limit below the horizon while the check holds (the pid's pull is dropped below). */
  const float pitch_cmd_deg =
      s->stalling ? -cfg->sc_pitch_cmd_limit_deg : pitch_command_deg(cfg, s);
  const float pitch_err = ha_clampf(pitch_cmd_deg - s->x[HA_X_PITCH_DEG],
                                    -cfg->sc_pitch_error_max_deg, cfg->sc_pitch_error_max_deg);
  t->roll_pd = cfg->sc_roll_kp * roll_err - cfg->sc_roll_kd * s->x[HA_X_P_DEG_S];
  t->roll_step = cfg->sc_roll_ki * roll_err * dt_s;
  /* The wing's lift beats height and speed: past the guard's load the nose is pushed down in
   * proportion, and the integrator may not pull against the push (HiL: pitching up to hold
   * height in the 47 deg bank it inherited, the HA stalled the wing at 61 ft/s). */
  const float excess_g = lift_excess_g(cfg, s);
  t->pitch_pd += cfg->sc_pitch_kp * pitch_err - cfg->sc_pitch_kd * s->x[HA_X_Q_DEG_S];
  t->pitch_step = cfg->sc_pitch_ki * pitch_err * dt_s;
  if (ha_greater(excess_g, 0.0f)) {
    t->pitch_pd -= cfg->sc_lift_push_deg_per_g * excess_g;
    t->pitch_step = ha_greater(t->pitch_step, 0.0f) ? 0.0f : t->pitch_step;
  }
}

/* The throttle loop's terms: the speed loop on a speed, pitch and power without one. */
static void throttle_terms(HaSafetyCtrlState *st, const HaAircraftConfig *cfg, const HaStateView *s,
                           int in_control, float dt_s, LoopTerms *t) {
  if (s->airborne && s->speed_known && s->attitude_ok) {
    const float speed_err = cfg->sc_target_ftps - s->ias_ftps;
    t->thr_pd += cfg->sc_throttle_kp_per_ftps * speed_err;
    t->thr_step = cfg->sc_throttle_ki_per_ft * speed_err * dt_s;
  } else if (in_control && s->attitude_ok) {
    /* Pitch and power: the nose at the attitude that holds the speed, the power for the height.
     * Whatever the HP or a speed loop fed a lying sensor left in the integrator fades (HiL: the
     * throttle cut to 0.05 on a tailwind's speed over the ground); less power than the trim
     * would slow the aircraft at that attitude, so the band's ceiling is the pitch term's. */
    st->throttle_integ = toward_zero(st->throttle_integ,
                                     cfg->sc_blind_fade_auth_per_s * dt_s * cfg->sc_throttle_half);
  }
  /* Power for height in both modes: below the band's middle, throttle_trim's margin to full in
   * proportion, full at the band's floor. With the speed known, the nose may rise only as far
   * as the speed pays, and the speed loop alone gave a turn's drag too little power (HiL
   * campaign seed 27 #4: 4 ft/s slow at throttle 0.6, pitch held at 2 deg, 158 ft lost). */
  if (s->airborne && s->attitude_ok && s->altitude_ok) {
    const float below_ft = cfg->sc_alt_mid_ft - s->x[HA_X_ALT_AGL_FT];
    t->thr_pd +=
        ha_clampf(cfg->sc_power_throttle_per_ft * below_ft, 0.0f, cfg->sc_power_throttle_max);
  }
}

static float aileron_deg(HaSafetyCtrlState *st, const HaAircraftConfig *cfg, const HaStateView *s,
                         const LoopTerms *t, int in_control, const HaSurfaces *applied) {
  const float aileron = pid(&st->roll_integ_deg, t->roll_pd, t->roll_step, cfg->aileron_limit_deg,
                            cfg->sc_aileron_integ_limit, in_control, applied->aileron_deg);
  /* Past the bank limit the integrator keeps no part that holds the bank, the one it tracked
   * from the HP or its own: the proportional term rolls the wing back at once (HiL campaign
   * seed 26 #91: the HA held the 33 deg bank it inherited for seconds, its integrator unwinding
   * at roll_ki, and a gust stalled the wing at 75 ft). Finite: x is clamped by ha_state_view. */
  if (in_control && s->attitude_ok &&
      ((ha_greater(s->x[HA_X_ROLL_DEG], cfg->sc_bank_limit_deg) &&
        ha_greater(st->roll_integ_deg, 0.0f)) ||
       (ha_greater(-cfg->sc_bank_limit_deg, s->x[HA_X_ROLL_DEG]) &&
        ha_greater(0.0f, st->roll_integ_deg)))) {
    st->roll_integ_deg = 0.0f;
    return ha_clampf(t->roll_pd, -cfg->aileron_limit_deg, cfg->aileron_limit_deg);
  }
  return aileron;
}

/* Elevator trailing edge down is positive (nose down): the loop works in nose-up degrees. */
static float nose_up_deg(HaSafetyCtrlState *st, const HaAircraftConfig *cfg, const HaStateView *s,
                         const LoopTerms *t, int in_control, const HaSurfaces *applied) {
  const float pitch_integ_limit = cfg->sc_elevator_integ_limit; /* pid's and the stop's */
  float nose_up = pid(&st->pitch_integ_deg, t->pitch_pd, t->pitch_step, cfg->elevator_limit_deg,
                      pitch_integ_limit, in_control, -applied->elevator_deg);
  if (s->stalling && ha_greater(st->pitch_integ_deg, 0.0f)) {
    st->pitch_integ_deg = 0.0f; /* no pull held, the one it tracked from the HP or its own */
    nose_up = ha_clampf(t->pitch_pd, -cfg->elevator_limit_deg, cfg->elevator_limit_deg);
  }
  /* The elevator stop: the HA's own pull never trims the wing at its stall (the generator holds
   * sc_elevator_pull_max_deg to airframe.yaml). Flying, the integrator is wound back to the stop
   * so that it does not hold a pull beyond it; tracking another controller, the surfaces it
   * inherits are the rate limiter's to ease. */
  if (ha_greater(nose_up, cfg->sc_elevator_pull_max_deg)) {
    if (in_control) {
      st->pitch_integ_deg =
          ha_clampf(st->pitch_integ_deg - (nose_up - cfg->sc_elevator_pull_max_deg),
                    -pitch_integ_limit, pitch_integ_limit);
    }
    nose_up = cfg->sc_elevator_pull_max_deg;
  }
  return nose_up;
}

void ha_safety_ctrl_step(HaSafetyCtrlState *st, const HaAircraftConfig *cfg, const HaStateView *s,
                         const HaSurfaces *applied, int in_control, float dt_s, HaSurfaces *out) {
  /* What depends on the configuration alone is the generator's (sc_target_ftps and the rest). */
  const float throttle_half = cfg->sc_throttle_half;
  const float throttle_mid = cfg->sc_throttle_mid;
  LoopTerms t = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
  /* Both loops fly about the airframe's trim, so what an integrator holds (and a blind HA fades
   * to zero) is the departure from it: the elevator is not neutral at the cruise of every
   * airframe (HiL: the Aerosonde's -7.6 deg faded to 0 dived it into the ground). */
  t.pitch_pd = -cfg->sc_elevator_trim_deg;
  t.thr_pd = cfg->sc_throttle_trim_offset;
  if (!s->attitude_ok && in_control) {
    /* Blind: nothing to close a loop on. What the integrators hold fades to the trims. */
    const float fade = cfg->sc_blind_fade_auth_per_s * dt_s;
    st->roll_integ_deg = toward_zero(st->roll_integ_deg, fade * cfg->aileron_limit_deg);
    st->pitch_integ_deg = toward_zero(st->pitch_integ_deg, fade * cfg->elevator_limit_deg);
    st->throttle_integ = toward_zero(st->throttle_integ, fade * throttle_half);
  }
  if (s->attitude_ok) {
    attitude_terms(cfg, s, dt_s, &t);
  }
  throttle_terms(st, cfg, s, in_control, dt_s, &t);
  out->aileron_deg = aileron_deg(st, cfg, s, &t, in_control, applied);
  out->elevator_deg = -nose_up_deg(st, cfg, s, &t, in_control, applied);
  /* Throttle is handled about the middle of its range so the same symmetric PID applies. */
  out->throttle = throttle_mid + pid(&st->throttle_integ, t.thr_pd, t.thr_step, throttle_half,
                                     cfg->sc_throttle_integ_limit, in_control,
                                     applied->throttle - throttle_mid);
  if (!s->airborne) {
    out->throttle = cfg->throttle_min; /* on the ground the motor idles */
  }
  /* Yaw damper only: rudder against the yaw rate (yaw left positive). */
  out->rudder_deg = ha_clampf(s->attitude_ok ? cfg->sc_yaw_damper_gain * s->x[HA_X_R_DEG_S] : 0.0f,
                              -cfg->rudder_limit_deg, cfg->rudder_limit_deg);
  /* Aileron and elevator come out of pid() inside +/-limit; the throttle's middle plus half the
   * range may round past either end. (A full ha_surfaces_saturate here cost 12 compares.) */
  out->throttle = ha_clampf(out->throttle, cfg->throttle_min, cfg->throttle_max);
}

void ha_safety_ctrl_reset(HaSafetyCtrlState *st) {
  st->roll_integ_deg = 0.0f;
  st->pitch_integ_deg = 0.0f;
  st->throttle_integ = 0.0f;
}
