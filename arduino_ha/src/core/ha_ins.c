#include "ha_ins.h"

#include <math.h>
#include <string.h>

#include "ha_num.h"

/* Units. */
#define HA_INS_FT_PER_M GEO_FT_PER_M
#define HA_INS_DEG_PER_RAD 57.295779513082320876f

/* What the VN-200 can report at all (datasheet ranges); a value outside is a corrupt packet,
 * and the bounds keep every conversion below finite. */
#define HA_INS_MAX_RATE_RADPS 35.0f /* gyro range +/-2000 deg/s */
#define HA_INS_MAX_SPEED_MPS 515.0f /* GNSS velocity limit, 500 m/s, plus margin */
#define HA_INS_MIN_ALT_M (-1000.0)  /* below the lowest ellipsoid height on earth */
#define HA_INS_MAX_ALT_M 18000.0    /* GNSS altitude limit */
/* Parked: vertical speed within the INS's noise on the ground. A sensor property, not the
 * aircraft's. */
#define HA_INS_PARKED_VDOWN_MPS 1.0f
#define HA_INS_MAX_ACCEL_MPS2 160.0f  /* accelerometer range +/-16 g */
#define HA_INS_G_PER_MPS2 0.10197162f /* 1 / standard gravity */

/* INS status error flags, bits 3-6. */
#define HA_INS_STATUS_ERRORS 0x0078u

void ha_ins_init(HaIns *ins) { memset(ins, 0, sizeof *ins); }

static int in_range_d(double v, double lo, double hi) { return v >= lo && v <= hi; }

/* Into [lo, hi]; NaN becomes lo. Used only on values already found in range, where it changes
 * nothing: it lets static analysis (Frama-C EVA) see the bounds the arithmetic relies on. */
static double clamp_d(double v, double lo, double hi) {
  if (v != v || v < lo) {
    return lo;
  }
  return v > hi ? hi : v;
}

/* A solution whose every field passed sample_in_range(), bounds made explicit. */
typedef struct {
  float yaw_deg, pitch_deg, roll_deg;
  float rate_radps[3];
  float vel_ned_mps[3];
  double lat_deg, lon_deg, alt_m;
} Checked;

static void checked_from(const HaInsSample *s, Checked *c) {
  size_t i;
  c->yaw_deg = ha_clampf(s->ypr_deg[0], -180.0f, 180.0f);
  c->pitch_deg = ha_clampf(s->ypr_deg[1], -90.0f, 90.0f);
  c->roll_deg = ha_clampf(s->ypr_deg[2], -180.0f, 180.0f);
  for (i = 0u; i < 3u; ++i) {
    c->rate_radps[i] =
        ha_clampf(s->angular_rate_radps[i], -HA_INS_MAX_RATE_RADPS, HA_INS_MAX_RATE_RADPS);
    c->vel_ned_mps[i] = ha_clampf(s->vel_ned_mps[i], -HA_INS_MAX_SPEED_MPS, HA_INS_MAX_SPEED_MPS);
  }
  c->lat_deg = clamp_d(s->lat_deg, -90.0, 90.0);
  c->lon_deg = clamp_d(s->lon_deg, -180.0, 180.0);
  c->alt_m = clamp_d(s->alt_m, HA_INS_MIN_ALT_M, HA_INS_MAX_ALT_M);
}

/* Every field the state is made of is present, finite and inside what the sensor can report.
 * The comparisons reject NaN and inf before any arithmetic touches them. */
static int sample_in_range(const HaInsSample *s) {
  int ok = (s->has & HA_INS_HAS_REQUIRED) == HA_INS_HAS_REQUIRED;
  size_t i;
  ok = ok && ha_in_range(s->ypr_deg[0], -180.0f, 180.0f);
  ok = ok && ha_in_range(s->ypr_deg[1], -90.0f, 90.0f);
  ok = ok && ha_in_range(s->ypr_deg[2], -180.0f, 180.0f);
  for (i = 0u; i < 3u; ++i) {
    ok = ok && ha_in_range(s->angular_rate_radps[i], -HA_INS_MAX_RATE_RADPS, HA_INS_MAX_RATE_RADPS);
    ok = ok && ha_in_range(s->vel_ned_mps[i], -HA_INS_MAX_SPEED_MPS, HA_INS_MAX_SPEED_MPS);
  }
  ok = ok && in_range_d(s->lat_deg, -90.0, 90.0);
  ok = ok && in_range_d(s->lon_deg, -180.0, 180.0);
  ok = ok && in_range_d(s->alt_m, HA_INS_MIN_ALT_M, HA_INS_MAX_ALT_M);
  return ok;
}

/* The INS says its solution is good: tracking, GNSS fix, no error flag. */
static int ins_tracking(uint16_t status) {
  return (status & 0x3u) == HA_INS_MODE_TRACKING && (status & 0x4u) != 0u &&
         (status & HA_INS_STATUS_ERRORS) == 0u;
}

/* Ground speed below the stall speed and hardly any vertical speed: the aircraft cannot be
 * flying. Only called on an in-range sample. */
static int parked(const HaAircraftConfig *cfg, const Checked *c) {
  const float stall_mps = cfg->stall_speed_ftps / (float)HA_INS_FT_PER_M;
  const float vn = c->vel_ned_mps[0];
  const float ve = c->vel_ned_mps[1];
  return vn * vn + ve * ve < stall_mps * stall_mps &&
         ha_in_range(c->vel_ned_mps[2], -HA_INS_PARKED_VDOWN_MPS, HA_INS_PARKED_VDOWN_MPS);
}

/* Home is the origin of the flat earth of geo_wgs84.h, the stack's one conversion. Only called
 * on an in-range sample, which geo_ref_init accepts. */
static void latch_home(HaIns *ins, const Checked *s) {
  if (geo_ref_init(&ins->home, s->lat_deg, s->lon_deg, s->alt_m)) {
    ins->home_latched = 1u;
    ins->home_seq += 1u;
  }
}

int ha_ins_update(HaIns *ins, const HaAircraftConfig *cfg, const HaInsSample *s,
                  uint8_t ha_on_ground, uint32_t now_us, HaInputs *in) {
  Checked c;
  int is_parked;
  /* A rejected solution is dropped without touching the state: the last good one stays, and
   * the core's state timeout, not one bad packet, decides when it is too old to trust. */
  if (!sample_in_range(s) || !ins_tracking(s->ins_status)) {
    ins->solutions_rejected += 1u;
    return 0;
  }
  checked_from(s, &c);
  is_parked = parked(cfg, &c);
  /* The first home needs the core's on-the-ground verdict as well as this solution parked: the
   * INS alone calls a level leg into a headwind parked, and would latch home in the air. */
  if (!ins->home_latched && ha_on_ground != 0u && (s->has & HA_INS_HAS_GPS_FIX) != 0u &&
      s->gps_fix >= HA_INS_GPS_FIX_3D && is_parked) {
    latch_home(ins, &c);
  }
  in->heading_deg = c.yaw_deg;
  in->pitch_deg = c.pitch_deg;
  in->roll_deg = c.roll_deg;
  /* Body x, y, z rates are p, q, r in the core's sign conventions. */
  in->p_deg_s = c.rate_radps[0] * HA_INS_DEG_PER_RAD;
  in->q_deg_s = c.rate_radps[1] * HA_INS_DEG_PER_RAD;
  in->r_deg_s = c.rate_radps[2] * HA_INS_DEG_PER_RAD;
  in->groundspeed_ftps =
      sqrtf(c.vel_ned_mps[0] * c.vel_ned_mps[0] + c.vel_ned_mps[1] * c.vel_ned_mps[1]) *
      (float)HA_INS_FT_PER_M;
  /* For the airspeed picture (ha_airdata.c): velocity over the ground, climb, height above sea
   * level (ellipsoid: the geoid's few tens of metres change the density by under 0.5%). */
  in->vel_north_ftps = c.vel_ned_mps[0] * (float)HA_INS_FT_PER_M;
  in->vel_east_ftps = c.vel_ned_mps[1] * (float)HA_INS_FT_PER_M;
  in->climb_ftps = -c.vel_ned_mps[2] * (float)HA_INS_FT_PER_M;
  in->altitude_msl_ft = (float)c.alt_m * (float)HA_INS_FT_PER_M;
  /* Lift pulls the body up (-z), so the specific force on z is -n g. A packet without it, or
   * past the sensor's range, leaves the load factor to the gyros. */
  in->accel_ok =
      (uint8_t)((s->has & HA_INS_HAS_ACCEL) != 0u &&
                ha_in_range(s->accel_mps2[2], -HA_INS_MAX_ACCEL_MPS2, HA_INS_MAX_ACCEL_MPS2));
  in->accel_load_factor =
      in->accel_ok ? -ha_clampf(s->accel_mps2[2], -HA_INS_MAX_ACCEL_MPS2, HA_INS_MAX_ACCEL_MPS2) *
                         HA_INS_G_PER_MPS2
                   : 1.0f;
  if (ins->home_latched) {
    const float agl_ft = (float)(c.alt_m - ins->home.alt_m) * (float)HA_INS_FT_PER_M;
    in->altitude_agl_ft = agl_ft;
    geo_to_ne_ft_f(&ins->home, c.lat_deg, c.lon_deg, &in->north_ft, &in->east_ft);
    /* The INS has no weight-on-wheels: parked and no higher than the airborne altitude. The
     * core adds its own airspeed check before it trusts this. */
    in->on_ground = (uint8_t)(is_parked && agl_ft <= cfg->airborne_agl_ft);
    in->home_unknown = 0u;
  } else {
    /* No home: no height and no place; parked is all the INS can say about the ground. */
    in->altitude_agl_ft = 0.0f;
    in->north_ft = 0.0f;
    in->east_ft = 0.0f;
    in->on_ground = (uint8_t)is_parked;
    in->home_unknown = 1u;
  }
  ins->last_lat_deg = c.lat_deg;
  ins->last_lon_deg = c.lon_deg;
  ins->last_alt_m = c.alt_m;
  ins->last_on_ground = (uint8_t)(ins->home_latched && in->on_ground);
  ins->last_used_us = now_us;
  in->state_valid = 1u;
  in->state_rx_us = now_us;
  ins->solutions_used += 1u;
  return 1;
}

int ha_ins_set_home(HaIns *ins, uint8_t ha_on_ground, uint8_t use_current, double lat_deg,
                    double lon_deg, double alt_m) {
  GeoRef moved = ins->home; /* every field defined, whatever geo_ref_init does */
  /* On the ground by the core's one rule, which also judged the INS state fresh by an age that
   * saturates: a wrapping difference of two clock readings would call a solution 2^32 us old
   * fresh. The adapter's own last solution must say parked and low too. */
  if (!ins->home_latched || ha_on_ground == 0u || ins->last_on_ground == 0u) {
    return HA_INS_SET_HOME_NOT_ON_GROUND;
  }
  if (use_current != 0u) {
    lat_deg = ins->last_lat_deg;
    lon_deg = ins->last_lon_deg;
    alt_m = ins->last_alt_m;
  }
  /* geo_ref_init checks range and NaN; the INS's altitude bounds apply as to any solution. */
  if (!in_range_d(alt_m, HA_INS_MIN_ALT_M, HA_INS_MAX_ALT_M) ||
      !geo_ref_init(&moved, lat_deg, lon_deg, alt_m)) {
    return HA_INS_SET_HOME_BAD_POSITION;
  }
  ins->home = moved;
  ins->home_seq += 1u;
  return HA_INS_SET_HOME_OK;
}

int ha_ins_restore_home(HaIns *ins, double lat_deg, double lon_deg, double alt_m,
                        uint32_t home_seq) {
  GeoRef kept = ins->home;
  if (!in_range_d(alt_m, HA_INS_MIN_ALT_M, HA_INS_MAX_ALT_M) ||
      !geo_ref_init(&kept, lat_deg, lon_deg, alt_m)) {
    return 0;
  }
  ins->home = kept;
  ins->home_latched = 1u;
  ins->home_seq = home_seq;
  return 1;
}
