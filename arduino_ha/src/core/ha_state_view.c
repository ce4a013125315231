#include "ha_checks.h"
#include "ha_num.h"

/* Physical plausibility, not aircraft limits: an attitude outside these is a broken message. */
#define HA_ROLL_SPAN_DEG 180.0f
#define HA_PITCH_SPAN_DEG 90.0f
#define HA_HEADING_SPAN_DEG 720.0f
#define HA_RATE_SPAN_DEG_S 2000.0f
#define HA_ALT_SPAN_FT 100000.0f
#define HA_POSITION_SPAN_FT 1.0e6f
#define HA_LOAD_SPAN_G 16.0f

static int attitude_plausible(const HaInputs *in) {
  return ha_within_span(in->roll_deg, HA_ROLL_SPAN_DEG) &&
         ha_within_span(in->pitch_deg, HA_PITCH_SPAN_DEG) &&
         ha_within_span(in->p_deg_s, HA_RATE_SPAN_DEG_S) &&
         ha_within_span(in->q_deg_s, HA_RATE_SPAN_DEG_S) &&
         ha_within_span(in->r_deg_s, HA_RATE_SPAN_DEG_S);
}

static int position_plausible(const HaInputs *in) {
  return ha_within_span(in->north_ft, HA_POSITION_SPAN_FT) &&
         ha_within_span(in->east_ft, HA_POSITION_SPAN_FT) &&
         ha_within_span(in->heading_deg, HA_HEADING_SPAN_DEG);
}

/* Every stored value is clamped to its plausible span even when its ok flag is set: the flag
 * says whether to trust it, the clamp guarantees later arithmetic cannot overflow. */
void ha_state_view(const HaAircraftConfig *cfg, const HaInputs *in, const HaHpCommand *cmd,
                   int have_cmd, const HaOwnSensors *own, HaStateView *out) {
  const int fresh = in->state_valid != 0u && own->state_age_us <= cfg->state_timeout_us;
  int j;
  for (j = 0; j < HA_X_DIM; ++j) {
    out->x[j] = cfg->x0[j];
  }
  out->attitude_ok = (uint8_t)(fresh && attitude_plausible(in));
  /* Before its first home the INS gives attitude, rates and speed, but no height or place. */
  out->altitude_ok = (uint8_t)(fresh && in->home_unknown == 0u &&
                               ha_within_span(in->altitude_agl_ft, HA_ALT_SPAN_FT));
  out->position_ok = (uint8_t)(fresh && in->home_unknown == 0u && position_plausible(in));
  out->airspeed_ok = (uint8_t)(own->airspeed_age_us <= cfg->airspeed_timeout_us);
  out->alpha_beta_ok =
      (uint8_t)(have_cmd && ha_finite(cmd->alpha_est_deg) && ha_finite(cmd->beta_est_deg));
  if (out->attitude_ok) {
    out->x[HA_X_ROLL_DEG] = ha_clampf(in->roll_deg, -HA_ROLL_SPAN_DEG, HA_ROLL_SPAN_DEG);
    out->x[HA_X_PITCH_DEG] = ha_clampf(in->pitch_deg, -HA_PITCH_SPAN_DEG, HA_PITCH_SPAN_DEG);
    out->x[HA_X_P_DEG_S] = ha_clampf(in->p_deg_s, -HA_RATE_SPAN_DEG_S, HA_RATE_SPAN_DEG_S);
    out->x[HA_X_Q_DEG_S] = ha_clampf(in->q_deg_s, -HA_RATE_SPAN_DEG_S, HA_RATE_SPAN_DEG_S);
    out->x[HA_X_R_DEG_S] = ha_clampf(in->r_deg_s, -HA_RATE_SPAN_DEG_S, HA_RATE_SPAN_DEG_S);
  }
  out->accel_load_factor =
      (fresh && in->accel_ok != 0u) ? ha_clampf(in->accel_load_factor, 0.0f, HA_LOAD_SPAN_G) : 0.0f;
  if (out->altitude_ok) {
    out->x[HA_X_ALT_AGL_FT] = ha_clampf(in->altitude_agl_ft, -HA_ALT_SPAN_FT, HA_ALT_SPAN_FT);
  }
  /* alpha and beta are the HP's estimates: without a command they stay at the centre and the
   * other checks decide (no command means the HA flies anyway). Beyond +/-180 deg an estimate
   * fails the alpha/beta check anyway; the clamp only keeps S_x arithmetic bounded. */
  if (out->alpha_beta_ok) {
    out->x[HA_X_ALPHA_DEG] = ha_clampf(cmd->alpha_est_deg, -HA_ROLL_SPAN_DEG, HA_ROLL_SPAN_DEG);
    out->x[HA_X_BETA_DEG] = ha_clampf(cmd->beta_est_deg, -HA_ROLL_SPAN_DEG, HA_ROLL_SPAN_DEG);
  }
  out->airspeed_ftps =
      out->airspeed_ok ? ha_clampf(own->airspeed_ftps, 0.0f, cfg->max_airspeed_ftps) : 0.0f;
  out->heading_deg = out->position_ok
                         ? ha_clampf(in->heading_deg, -HA_HEADING_SPAN_DEG, HA_HEADING_SPAN_DEG)
                         : 0.0f;
  out->north_ft =
      out->position_ok ? ha_clampf(in->north_ft, -HA_POSITION_SPAN_FT, HA_POSITION_SPAN_FT) : 0.0f;
  out->east_ft =
      out->position_ok ? ha_clampf(in->east_ft, -HA_POSITION_SPAN_FT, HA_POSITION_SPAN_FT) : 0.0f;
  out->still =
      (uint8_t)(out->attitude_ok && ha_within_span(in->roll_deg, cfg->self_test_max_tilt_deg) &&
                ha_within_span(in->pitch_deg, cfg->self_test_max_tilt_deg) &&
                ha_within_span(in->p_deg_s, cfg->self_test_max_rate_deg_s) &&
                ha_within_span(in->q_deg_s, cfg->self_test_max_rate_deg_s) &&
                ha_within_span(in->r_deg_s, cfg->self_test_max_rate_deg_s) &&
                ha_within_span(in->groundspeed_ftps, cfg->self_test_max_groundspeed_ftps));
  /* Signals for the core's airborne latch. Each alone says flying: a pitot above stall, the
   * INS above alt0, the INS not parked (moving or climbing). A landing needs every sensor to
   * say so: the pitot alive and below stall (a dead pitot cannot tell 55 ft/s into a headwind
   * from parked) and a fresh INS parked at a known height. Before its first home the INS has no
   * height to tell, so it must be still (stopped over the ground, level, no rates), which no
   * flight into a headwind is. */
  {
    const int fast = out->airspeed_ok && ha_greater(out->airspeed_ftps, cfg->stall_speed_ftps);
    const int high = out->altitude_ok && ha_greater(out->x[HA_X_ALT_AGL_FT], cfg->airborne_agl_ft);
    const int ins_low = out->altitude_ok ? !high : (in->home_unknown != 0u && out->still);
    out->flying_evidence = (uint8_t)(fast || high || (fresh && in->on_ground == 0u));
    out->landed_evidence =
        (uint8_t)(out->airspeed_ok && !fast && fresh && in->on_ground != 0u && ins_low);
  }
  out->airborne = 1u; /* until the core has decided */
  out->on_ground = 0u;
  out->parked = 0u;
}
