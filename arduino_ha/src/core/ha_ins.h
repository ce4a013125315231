/* The INS adapter: one VN-200 solution in, the aircraft-state fields of HaInputs out, in the
 * core's units and frames. Portable C99, no heap, no recursion, time passed in; independent of
 * the VN-200 headers (the board layer copies the decoded packet into HaInsSample).
 *
 * Frames: the VN-200 reports yaw/pitch/roll of the body relative to local NED and body rates in
 * its own body frame (x forward, y right, z down), which are exactly the core's conventions
 * (roll right wing down positive, pitch nose up positive, heading clockwise from true north,
 * r nose right positive); only units change (rad/s -> deg/s, m -> ft).
 *
 * Home: the position origin the HA circles and the zero of altitude AGL. It is latched once, at
 * the first valid solution with a 3D GNSS fix taken parked while the core says the aircraft is on
 * the ground (HaOutputs.on_ground: the airborne latch clear, the pitot alive and below stall, the
 * INS parked; the INS alone calls a level leg into a headwind parked), and never moved afterwards
 * but by SET_HOME on the ground: re-latching in flight would shift the circle and the ceiling.
 * Until home is latched the state carries attitude, rates, groundspeed and parked but no height
 * or position (HaInputs.home_unknown): the core keeps the HA in control, which can still level
 * the wings and hold the airspeed. A home kept across a reset of the HA comes back through
 * ha_ins_restore_home (ha_app.c, the Board's retained words). */
#ifndef HA_INS_H
#define HA_INS_H

#include <stdint.h>

#include "../generated/ha_config.h"
#include "geo_wgs84.h"
#include "ha_core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* HaInsSample.has bits: which fields the packet carried. */
#define HA_INS_HAS_YPR 0x01u
#define HA_INS_HAS_RATE 0x02u
#define HA_INS_HAS_POSITION 0x04u
#define HA_INS_HAS_VEL_NED 0x08u
#define HA_INS_HAS_STATUS 0x10u
#define HA_INS_HAS_GPS_FIX 0x20u
#define HA_INS_HAS_ACCEL 0x40u /* optional: without it the load factor is the gyros' alone */
#define HA_INS_HAS_REQUIRED \
  (HA_INS_HAS_YPR | HA_INS_HAS_RATE | HA_INS_HAS_POSITION | HA_INS_HAS_VEL_NED | HA_INS_HAS_STATUS)

/* INS status word (VN-200 manual, "INS Status"): mode in bits 0-1 (2 = tracking, the solution is
 * good), GNSS fix in bit 2, error flags in bits 3-6. */
#define HA_INS_MODE_TRACKING 2u
#define HA_INS_GPS_FIX_3D 3u

/* One INS solution, as the sensor sends it (units in the names). */
typedef struct {
  uint8_t has;                    /* HA_INS_HAS_* */
  float ypr_deg[3];               /* yaw, pitch, roll */
  float angular_rate_radps[3];    /* body x, y, z */
  double lat_deg, lon_deg, alt_m; /* WGS84, ellipsoid height */
  float vel_ned_mps[3];
  float accel_mps2[3]; /* body x, y, z (z down): the specific force, -g on z in level flight */
  uint16_t ins_status;
  uint8_t gps_fix; /* 0 none, 1 time only, 2 2D, 3 3D */
} HaInsSample;

typedef struct {
  uint8_t home_latched;
  /* Home and the flat earth's scale there (geo_wgs84.h), valid once home_latched. */
  GeoRef home;
  uint32_t home_seq; /* +1 every time home is set: the link republishes it on a change */
  /* The last solution used: where "here" is for a SET_HOME, and whether the aircraft is on the
   * ground (parked, no higher than the airborne altitude). */
  double last_lat_deg, last_lon_deg, last_alt_m;
  uint8_t last_on_ground;
  uint32_t last_used_us;
  uint32_t solutions_used;     /* solutions that made the state valid */
  uint32_t solutions_rejected; /* solutions that left it invalid (status, range, no home yet) */
} HaIns;

void ha_ins_init(HaIns *ins);

/* Applies one solution received at now_us. Returns 1 and writes every state field of *inputs
 * with state_valid = 1 and state_rx_us = now_us when the INS is tracking with a GNSS fix and no
 * error flag, and every field it needs is present, finite and inside the sensor's range (before
 * home is latched with home_unknown = 1: no altitude AGL, no position). Otherwise returns 0 and
 * leaves every field alone: one rejected packet is not a lost INS, the core's state timeout ages
 * the last good state out.
 * ha_on_ground is the core's verdict of the last period (HaOutputs.on_ground): home latches only
 * on it. cfg supplies the aircraft's stall speed and airborne altitude (on_ground, parked). */
int ha_ins_update(HaIns *ins, const HaAircraftConfig *cfg, const HaInsSample *sample,
                  uint8_t ha_on_ground, uint32_t now_us, HaInputs *inputs);

/* The operator's SET_HOME (MAV_CMD_DO_SET_HOME through the ground station): moves home to
 * (lat_deg, lon_deg, alt_m), or to where the aircraft is when use_current is nonzero. Accepted
 * (returns HA_INS_SET_HOME_OK, home_seq advances) only on the ground by the core's one rule:
 * ha_on_ground is its latest verdict (HaOutputs.on_ground, which also says the INS state is fresh,
 * by an age that saturates), home latched, and the last used solution parked below the airborne
 * altitude. Otherwise home stays where it is and the return value says why. */
#define HA_INS_SET_HOME_OK 0
#define HA_INS_SET_HOME_NOT_ON_GROUND 1 /* flying, or no fresh solution to tell */
#define HA_INS_SET_HOME_BAD_POSITION 2  /* not finite or out of range */
int ha_ins_set_home(HaIns *ins, uint8_t ha_on_ground, uint8_t use_current, double lat_deg,
                    double lon_deg, double alt_m);

/* Home as kept across a reset of the HA (ha_retained.h): latched again at (lat_deg, lon_deg,
 * alt_m) with home_seq, so the link republishes the same home. Returns 1 when taken (in range),
 * else 0 and the adapter stays without home. */
int ha_ins_restore_home(HaIns *ins, double lat_deg, double lon_deg, double alt_m,
                        uint32_t home_seq);

#ifdef __cplusplus
}
#endif

#endif /* HA_INS_H */
