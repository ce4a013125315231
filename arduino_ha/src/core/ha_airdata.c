#include "ha_airdata.h"

#include <math.h>

#include "ha_num.h"

/* Physical plausibility, not aircraft limits (as in ha_state_view.c): the VN-200 reports at most
 * 500 m/s; an attitude or heading beyond these is a broken message. */
#define HA_AD_SPEED_SPAN_FTPS 2000.0f
#define HA_AD_HEADING_SPAN_DEG 720.0f
/* The ISA fit below holds from below the Dead Sea to above any field a glider like this flies
 * from; a height outside is clamped to it. */
#define HA_AD_MSL_MIN_FT (-2000.0f)
#define HA_AD_MSL_MAX_FT 20000.0f
/* The density is recomputed only once the height has moved this much: 0.15% of TAS. */
#define HA_AD_DENSITY_STEP_FT 100.0f
/* ISA troposphere: TAS / IAS = (rho0 / rho)^0.5 = (1 - 6.8756e-6 h)^-2.12795 (h in ft), fitted by
 * a quadratic in h within 0.11% over [HA_AD_MSL_MIN_FT, HA_AD_MSL_MAX_FT]: no powf on the Due. */
#define HA_AD_ISA_C0 1.0001669f
#define HA_AD_ISA_C1 1.4295060e-5f
#define HA_AD_ISA_C2 2.0683031e-10f
/* g in ft/s^2, for the load factor from the pitch rate. */
#define HA_AD_G_FTPS2 32.174f
/* Below this the flight path has no direction to speak of. */
#define HA_AD_MIN_SPEED_FTPS 1.0f
#define HA_AD_RAD_PER_DEG 0.017453293f

static void set_density(HaAirdata *a, float msl_ft) {
  a->density_below_ft = msl_ft - HA_AD_DENSITY_STEP_FT;
  a->density_above_ft = msl_ft + HA_AD_DENSITY_STEP_FT;
  a->tas_per_ias = HA_AD_ISA_C0 + msl_ft * (HA_AD_ISA_C1 + msl_ft * HA_AD_ISA_C2);
  a->ias_per_tas = 1.0f / a->tas_per_ias; /* once per change of height, not per period */
}

void ha_airdata_init(HaAirdata *a) {
  a->wind_north_ftps = 0.0f;
  a->wind_east_ftps = 0.0f;
  a->wind_learned_us = 0u;
  a->pitot_doubted_us = UINT32_MAX;
  a->last_reading_ftps = 0.0f;
  a->same_reading_us = 0u;
  set_density(a, 0.0f);
}

static int velocity_from(const HaInputs *in, HaVelocity *v) {
  const float span = HA_AD_SPEED_SPAN_FTPS;
  v->north_ftps = ha_clampf(in->vel_north_ftps, -span, span);
  v->east_ftps = ha_clampf(in->vel_east_ftps, -span, span);
  v->climb_ftps = ha_clampf(in->climb_ftps, -span, span);
  return ha_within_span(in->vel_north_ftps, span) && ha_within_span(in->vel_east_ftps, span) &&
         ha_within_span(in->climb_ftps, span);
}

/* The velocity less the wind, squared: the true airspeed it implies (the air not rising). */
static float inertial_tas_sq(float wind_north, float wind_east, const HaVelocity *v) {
  const float n = v->north_ftps - wind_north;
  const float e = v->east_ftps - wind_east;
  return n * n + e * e + v->climb_ftps * v->climb_ftps;
}

static int wind_known(const HaAirdata *a, const HaAircraftConfig *cfg) {
  return a->wind_learned_us >= cfg->wind_known_us;
}

/* Two-sided: |TAS - inertial TAS| <= tolerance, in squares (no root): reading low (blocked,
 * zeroed) and reading high (stuck, iced) alike. Before the wind is known, the tolerance is the
 * strongest wind flown in, from any direction. */
static int pitot_agrees(const HaAirdata *a, const HaAircraftConfig *cfg, const HaVelocity *v,
                        float tas) {
  const float tol = wind_known(a, cfg) ? cfg->airspeed_tolerance_ftps : cfg->max_wind_ftps;
  const float ref_sq = inertial_tas_sq(a->wind_north_ftps, a->wind_east_ftps, v);
  const float low = tas - tol;
  const float high = tas + tol;
  const int not_high = !ha_greater(low, 0.0f) || !ha_greater(low * low, ref_sq);
  return not_high && !ha_greater(ref_sq, high * high);
}

/* The heading's unit vector (north, east), from Taylor polynomials on [0, 90] deg after folding
 * (within 0.02, 2% of TAS in the wind: below the tolerance): no sinf/cosf, some 1,000 soft-float
 * instructions each on the Due. */
static void heading_unit(HaAirdata *a, float heading_deg) {
  /* Folded by integer compares on the bits (ha_greater), no floorf: [-720, 720] to [-180, 180],
   * then to [0, 90] with the signs of north and east. */
  float h = ha_clampf(heading_deg, -HA_AD_HEADING_SPAN_DEG, HA_AD_HEADING_SPAN_DEG);
  float deg, r, r2, c, sn;
  int west, south;
  if (ha_greater(h, 180.0f)) {
    h -= 360.0f;
  }
  if (ha_greater(h, 180.0f)) {
    h -= 360.0f;
  }
  if (ha_greater(-180.0f, h)) {
    h += 360.0f;
  }
  if (ha_greater(-180.0f, h)) {
    h += 360.0f;
  }
  west = ha_greater(0.0f, h);
  deg = west ? -h : h;
  south = ha_greater(deg, 90.0f);
  if (south) {
    deg = 180.0f - deg;
  }
  r = deg * HA_AD_RAD_PER_DEG;
  r2 = r * r;
  c = 1.0f + r2 * (-0.5f + r2 * (1.0f / 24.0f));
  sn = r * (1.0f + r2 * (-1.0f / 6.0f + r2 * (1.0f / 120.0f)));
  a->heading_north = south ? -c : c;
  a->heading_east = west ? -sn : sn;
}

/* The wind is what the velocity over the ground and the air's velocity (the pitot's TAS along
 * the heading) disagree by, followed slowly (wind_per_s, per period) and bounded by
 * max_wind_ftps. Learnt only in near-level flight (climb below a quarter of the speed: the
 * horizontal TAS is then within 3%), where the pitot reads the relative wind along its axis. */
static void learn_wind(HaAirdata *a, const HaAircraftConfig *cfg, const HaVelocity *v, float tas,
                       uint32_t dt_us) {
  const float k = cfg->wind_per_period;
  const float max = cfg->max_wind_ftps;
  float n, e, w_sq;
  if (ha_greater(4.0f * (ha_greater(0.0f, v->climb_ftps) ? -v->climb_ftps : v->climb_ftps), tas)) {
    return;
  }
  n = a->wind_north_ftps + k * (v->north_ftps - tas * a->heading_north - a->wind_north_ftps);
  e = a->wind_east_ftps + k * (v->east_ftps - tas * a->heading_east - a->wind_east_ftps);
  w_sq = n * n + e * e;
  if (w_sq > cfg->max_wind_sq) { /* a float compare: EVA then knows the root is above max */
    const float scale = max / sqrtf(w_sq); /* rare: only at the bound */
    n *= scale;
    e *= scale;
  }
  a->wind_north_ftps = ha_clampf(n, -max, max);
  a->wind_east_ftps = ha_clampf(e, -max, max);
  a->wind_learned_us = ha_add_sat(a->wind_learned_us, dt_us);
}

/* The density at the INS's height, recomputed once per HA_AD_DENSITY_STEP_FT of climb. */
static void track_density(HaAirdata *a, const HaInputs *in) {
  const float h = ha_clampf(in->altitude_msl_ft, HA_AD_MSL_MIN_FT, HA_AD_MSL_MAX_FT);
  if (ha_greater(h, a->density_above_ft) || ha_greater(a->density_below_ft, h)) {
    set_density(a, h);
  }
}

/* Stuck: the same nonzero reading, to the last bit, for pitot_stuck_us. The AMS5812's noise
 * (some 6 counts) moves every read of a live sensor; an iced or frozen one repeats itself while
 * the aircraft's speed goes its own way, and a stuck reading inside the wind's tolerance would
 * otherwise be believed for good (PX4's airspeed checks test the same). Zero is the sensor's
 * clipped reading at rest, not a stuck one (reading low is the two-sided test's). */
static int pitot_stuck(HaAirdata *a, const HaAircraftConfig *cfg, int read, float ias_ftps,
                       uint32_t dt_us) {
  const int same = read && ha_order_key(ias_ftps) == ha_order_key(a->last_reading_ftps) &&
                   ha_greater(ias_ftps, 0.0f);
  a->same_reading_us = same ? ha_add_sat(a->same_reading_us, dt_us) : 0u;
  if (read) {
    a->last_reading_ftps = ias_ftps;
  }
  return a->same_reading_us >= cfg->pitot_stuck_us;
}

int ha_airdata_track(HaAirdata *a, const HaAircraftConfig *cfg, const HaInputs *in, int ins_fresh,
                     int read, float ias_ftps, uint32_t dt_us) {
  int agrees = !pitot_stuck(a, cfg, read, ias_ftps, dt_us);
  if (ins_fresh && ha_within_span(in->heading_deg, HA_AD_HEADING_SPAN_DEG)) {
    heading_unit(a, in->heading_deg);
  }
  a->velocity_ok = (uint8_t)(ins_fresh && velocity_from(in, &a->velocity));
  if (a->velocity_ok) {
    const float tas = ias_ftps * a->tas_per_ias;
    track_density(a, in);
    agrees = agrees && (!read || pitot_agrees(a, cfg, &a->velocity, tas));
    if (read && agrees && ha_greater(ias_ftps, cfg->stall_speed_ftps)) {
      learn_wind(a, cfg, &a->velocity, tas, dt_us);
    }
  }
  a->pitot_doubted_us = (read && agrees) ? 0u : ha_add_sat(a->pitot_doubted_us, dt_us);
  if (a->pitot_doubted_us >= cfg->wind_forget_us) {
    a->wind_learned_us = 0u; /* doubted this long, the wind may have changed: unknown again */
  }
  return agrees;
}

/* The cosine of the bank, 1 / load factor of a level coordinated turn (within 0.01 to 75 deg);
 * at 90 deg and beyond no level turn exists: 0. */
static float bank_cos(float roll_deg) {
  const float r = (ha_greater(0.0f, roll_deg) ? -roll_deg : roll_deg) * HA_AD_RAD_PER_DEG;
  const float r2 = r * r;
  if (!ha_greater(1.5707964f, r)) {
    return 0.0f;
  }
  return 1.0f + r2 * (-0.5f + r2 * (1.0f / 24.0f));
}

void ha_airdata_view(const HaAirdata *a, const HaAircraftConfig *cfg, HaStateView *v) {
  const HaVelocity *vel = &a->velocity;
  const int ins = v->attitude_ok && a->velocity_ok;                    /* both fresh this period */
  v->cos_bank = v->attitude_ok ? bank_cos(v->x[HA_X_ROLL_DEG]) : 1.0f; /* roll already clamped */
  v->heading_north = a->heading_north;
  v->heading_east = a->heading_east;
  v->speed_ok = (uint8_t)(v->airspeed_ok || ins);
  /* ... but the INS's velocity is the airspeed only less a known wind. Before it is known (or
   * once forgotten) the speed over the ground is the airspeed plus a tailwind: flown by, a
   * believed 62 ft/s was a true 48 and the wing stalled 2.7 s (HiL: the pitot zeroed in 4.7 m/s
   * and turbulence). The safety controller then flies pitch and power; the checks may still
   * judge by it (a stall signature, or a takeover the pitot's doubt makes anyway). */
  v->speed_known = (uint8_t)(v->airspeed_ok || (ins && wind_known(a, cfg)));
  v->ias_ftps = 0.0f;
  v->tas_ftps = 0.0f;
  v->path_tas_sq = 0.0f;
  v->climb_ftps = ins ? vel->climb_ftps : 0.0f;
  if (v->airspeed_ok) {
    v->ias_ftps = v->airspeed_ftps;
    v->tas_ftps = v->airspeed_ftps * a->tas_per_ias;
  } else if (ins) {
    /* The pitot dead or doubted: the INS less the wind once known; a wind learnt only partly
     * may be what the pitot, now doubted, taught it (stuck high reads as a headwind), so until
     * then the speed over the ground. */
    const int known = wind_known(a, cfg);
    const float tas_ftps = sqrtf(
        inertial_tas_sq(known ? a->wind_north_ftps : 0.0f, known ? a->wind_east_ftps : 0.0f, vel));
    v->tas_ftps = ha_clampf(tas_ftps, 0.0f, cfg->max_airspeed_ftps);
    v->ias_ftps = v->tas_ftps * a->ias_per_tas;
  }
  /* The load factor without an accelerometer: gravity's share, cos(bank) (cos(pitch) taken as 1:
   * within 4% to 15 deg of pitch, and never low), plus the turn of the velocity the body's pitch
   * rate makes, V q / g. In a level turn that is 1 / cos(bank); in a pull the pitch rate leads
   * the load, so an accelerated stall shows before the wing reaches it (HiL accelerated_stall:
   * 2 g at 65 ft/s while the alpha was 4 deg). Rates and attitude are clamped by ha_state_view,
   * the speed to max_airspeed_ftps. */
  v->load_factor = 1.0f;
  if (v->attitude_ok) {
    v->load_factor =
        v->cos_bank + v->tas_ftps * v->x[HA_X_Q_DEG_S] * (HA_AD_RAD_PER_DEG / HA_AD_G_FTPS2);
  }
  /* The wing's load for the lift guard: the accelerometer's as well, where the INS sends it. A
   * vertical gust raises the angle of attack and the load with no pitch rate; the gyros miss it
   * (HiL, moderate turbulence: 1.5 to 1.8 g at 53 to 58 ft/s with the gyros' 1.0, the HA
   * pulling for height and the wing past its stall angle for up to 0.2 s). The stall check
   * keeps the gyros' alone: a gust's load is not the HP's doing. */
  v->lift_load_factor =
      ha_greater(v->accel_load_factor, v->load_factor) ? v->accel_load_factor : v->load_factor;
  /* Near the stall: at or below the 1 g hand-back speed, where a stalled glide flies (the
   * wing's lift past the break, post_stall_cl_fraction of its maximum, holds 1 g at some 1.15 x
   * the stall speed). Only there is the INS's angle of attack looked at (ha_checks.c): its
   * flight path cannot see the air move nor a sideslip in a bank, and its errors reach the
   * stall's margin (HiL: STALL at a true 3.6 deg in a 33 deg bank at 57 ft/s, a 31 ft/s wind and
   * light turbulence); the load factor covers the banked and the pulled stall. */
  v->ias_sq = v->ias_ftps * v->ias_ftps;
  v->near_stall = (uint8_t)(v->speed_ok && !ha_greater(v->ias_sq, cfg->handback_airspeed_sq));
  /* The flight path's speed is the INS's less the wind as far as it is learnt, never the
   * pitot's: a pitot reading low but still believed made climb / TAS a dive twice as steep,
   * and the angle of attack a stall (HiL pitot_failure low). The path angle is small, so the
   * wind's error in it is too. Squared: the check needs no root. */
  if (ins && v->near_stall) {
    v->path_tas_sq = inertial_tas_sq(a->wind_north_ftps, a->wind_east_ftps, vel);
  }
  /* Pitch less flight path needs a direction of flight: the INS's velocity and climb. */
  v->alpha_ok = (uint8_t)(ins && v->near_stall && ha_greater(v->path_tas_sq, HA_AD_MIN_SPEED_FTPS));
}
