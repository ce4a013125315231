#include "bench_inputs.h"

#include <math.h>
#include <string.h>

/* Timeline segments, in periods. Long enough that recovery (the stable window) completes. */
#define SEGMENT_PERIODS 400u
#define SEGMENT_COUNT 10u

static uint32_t next_random(HaBenchTimeline *t) {
  /* xorshift32: cheap, deterministic, identical on every machine. */
  uint32_t x = t->rng;
  x ^= x << 13;
  x ^= x >> 17;
  x ^= x << 5;
  t->rng = x;
  return x;
}

/* Uniform in [lo, hi]. */
static float uniform(HaBenchTimeline *t, float lo, float hi) {
  const float unit = (float)(next_random(t) >> 8) * (1.0f / 16777216.0f);
  return lo + (hi - lo) * unit;
}

static float from_bits(uint32_t bits) {
  float f;
  memcpy(&f, &bits, sizeof f);
  return f;
}

/* A value no sane sensor or controller produces: NaN, +/-inf, huge or denormal. */
static float garbage(HaBenchTimeline *t) {
  switch (next_random(t) % 6u) {
    case 0u:
      return from_bits(0x7FC00000u); /* quiet NaN */
    case 1u:
      return from_bits(0x7F800000u); /* +inf */
    case 2u:
      return from_bits(0xFF800000u); /* -inf */
    case 3u:
      return 3.0e38f;
    case 4u:
      return from_bits(0x00000001u); /* smallest denormal */
    default:
      return -1.0e30f;
  }
}

static uint16_t rc_pulse(const HaAircraftConfig *cfg, float fraction) {
  const float span = (float)(cfg->rc_pulse_max_us - cfg->rc_pulse_min_us);
  return (uint16_t)((float)cfg->rc_pulse_min_us + span * fraction);
}

void ha_bench_timeline_init(HaBenchTimeline *t, const HaAircraftConfig *cfg, uint32_t seed) {
  t->rng = seed != 0u ? seed : 0x9E3779B9u;
  t->period = 0u;
  t->now_us = 0xFFFF0000u; /* start near the wrap so it is crossed during the run */
  t->seq = 1u;
  t->cfg = cfg;
}

/* Flight state: level-ish flight inside the region, above stall, below the ceiling. */
static void fly_level(HaBenchTimeline *t, const HaAircraftConfig *cfg, HaInputs *in) {
  in->airspeed_ftps = uniform(t, cfg->stall_speed_ftps * 1.3f, cfg->stall_speed_ftps * 2.0f);
  in->roll_deg = uniform(t, -20.0f, 20.0f);
  in->pitch_deg = uniform(t, -8.0f, 8.0f);
  in->heading_deg = uniform(t, -720.0f, 720.0f);
  in->p_deg_s = uniform(t, -30.0f, 30.0f);
  in->q_deg_s = uniform(t, -30.0f, 30.0f);
  in->r_deg_s = uniform(t, -30.0f, 30.0f);
  in->altitude_agl_ft = uniform(t, cfg->airborne_agl_ft * 2.0f, cfg->ceiling_agl_ft * 0.8f);
  in->north_ft = uniform(t, -3000.0f, 3000.0f);
  in->east_ft = uniform(t, -3000.0f, 3000.0f);
  in->groundspeed_ftps = uniform(t, cfg->stall_speed_ftps, cfg->stall_speed_ftps * 2.0f);
  {
    /* The INS's velocity: the airspeed along the heading plus a steady 10 ft/s wind from the
     * north-west, a climb or sink of a few ft/s at an angle of attack of 0 to 5 deg, and a height
     * above sea level that wanders by more than the density's recompute step. */
    const float heading_rad = in->heading_deg * 0.017453293f;
    const float climb_ftps = uniform(t, -4.0f, 4.0f);
    in->vel_north_ftps = in->airspeed_ftps * cosf(heading_rad) - 7.07f;
    in->vel_east_ftps = in->airspeed_ftps * sinf(heading_rad) + 7.07f;
    in->groundspeed_ftps =
        sqrtf(in->vel_north_ftps * in->vel_north_ftps + in->vel_east_ftps * in->vel_east_ftps);
    in->climb_ftps = climb_ftps;
    in->pitch_deg = climb_ftps / in->airspeed_ftps * 57.29578f + uniform(t, 0.0f, 5.0f);
    in->altitude_msl_ft = 600.0f + in->altitude_agl_ft + uniform(t, -200.0f, 200.0f);
  }
  in->on_ground = 0u;
  in->state_valid = 1u;
}

/* The sticks anywhere, the pilot-in-command switch off. */
static void rc_sticks(HaBenchTimeline *t, const HaAircraftConfig *cfg, HaInputs *in) {
  uint32_t i;
  in->rc.valid = 1u;
  for (i = 0u; i < (uint32_t)HA_RC_CHANNELS; ++i) {
    in->rc.pulse_us[i] = rc_pulse(cfg, uniform(t, 0.0f, 1.0f));
  }
  in->rc.pulse_us[HA_RC_PIC] = (uint16_t)(cfg->pic_threshold_us - 200u);
}

/* A healthy HP's command of this period, inside S_u (its CRC is added once it is final). */
static void healthy_command(HaBenchTimeline *t, const HaAircraftConfig *cfg, HaHpCommand *cmd) {
  memset(cmd, 0, sizeof *cmd);
  cmd->seq = t->seq++;
  cmd->stamp_sec = t->now_us / 1000000u;
  cmd->stamp_nsec = (t->now_us % 1000000u) * 1000u;
  cmd->throttle = uniform(t, cfg->throttle_min, cfg->throttle_max);
  /* No more nose-up than the pull limit: a pull past it is refused in flight (REASON_PULL) and
   * would keep the timeline's HP out of control, unmeasured. */
  cmd->elevator_deg = uniform(t, -cfg->elevator_pull_limit_deg, cfg->elevator_limit_deg) * 0.9f;
  cmd->aileron_deg = uniform(t, -cfg->aileron_limit_deg, cfg->aileron_limit_deg) * 0.9f;
  cmd->rudder_deg = uniform(t, -cfg->rudder_limit_deg, cfg->rudder_limit_deg) * 0.9f;
  cmd->alpha_est_deg = uniform(t, -2.0f, 6.0f); /* inside the stall alpha of limits.yaml */
  cmd->beta_est_deg = uniform(t, -5.0f, 5.0f);
  cmd->estimator_converged = 1u;
  cmd->sensor_links_healthy = 1u;
}

/* The segment's fault on this period's inputs and command; returns whether the command is sent. */
static int apply_segment(HaBenchTimeline *t, const HaAircraftConfig *cfg, uint32_t segment,
                         HaInputs *in, HaHpCommand *cmd) {
  switch (segment) {
    case 1u: /* HP crashed: silence */
      return 0;
    case 2u: /* late every other period */
      return (t->period % 2u) == 0u;
    case 3u: /* garbage in the command and the state */
      cmd->aileron_deg = garbage(t);
      cmd->alpha_est_deg = garbage(t);
      in->roll_deg = garbage(t);
      in->airspeed_ftps = garbage(t);
      break;
    case 4u: /* command outside S_u */
      cmd->elevator_deg = cfg->elevator_limit_deg * uniform(t, 1.01f, 3.0f);
      break;
    case 5u: /* stall, then above the ceiling, then outside S_x */
      in->airspeed_ftps = cfg->stall_speed_ftps * 0.8f;
      if ((t->period % 3u) == 1u) {
        in->altitude_agl_ft = cfg->ceiling_agl_ft * 1.1f;
      } else if ((t->period % 3u) == 2u) {
        in->roll_deg = 80.0f;
      }
      break;
    case 6u: /* frozen HP: the same sequence number again and again */
      cmd->seq = 7u;
      break;
    case 7u: /* pilot in command, part of the time with the receiver lost */
      in->rc.pulse_us[HA_RC_PIC] = (uint16_t)(cfg->pic_threshold_us + 200u);
      in->rc.valid = (uint8_t)((t->period % 50u) != 0u);
      break;
    default: /* 0, 8, 9: healthy HP; after a fault this is the recovery to the HP */
      break;
  }
  return 1;
}

uint32_t ha_bench_timeline_next(HaBenchTimeline *t, HaInputs *in) {
  const HaAircraftConfig *cfg = t->cfg;
  const uint32_t segment = (t->period / SEGMENT_PERIODS) % SEGMENT_COUNT;
  const uint32_t jitter_us = next_random(t) % 200u;
  HaHpCommand cmd;

  t->now_us += cfg->period_us;
  ++t->period;
  fly_level(t, cfg, in);
  in->state_rx_us = t->now_us - jitter_us;
  (void)uniform(t, 10.0f, 12.6f); /* was the battery's, which the core no longer takes */
  rc_sticks(t, cfg, in);
  healthy_command(t, cfg, &cmd);
  if (apply_segment(t, cfg, segment, in, &cmd)) {
    cmd.crc32 = ha_hp_command_compute_crc(&cmd);
    if (segment == 6u && (t->period % 4u) == 0u) {
      cmd.crc32 ^= 0x00010000u; /* a corrupted frame now and then */
    }
    /* As the link delivers it (ha_inputs_put_hp_command, src/firmware/ha_app.c): the core alone
     * is measured here. */
    in->hp_cmd = cmd;
    in->hp_cmd_rx_us = t->now_us - jitter_us;
    in->hp_cmd_count++;
  }
  return t->now_us;
}
