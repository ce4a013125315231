/* The checks of the decision logic. Each check is one function that only produces a flag; the
 * policy (ha_policy.c) alone decides what the flags mean. */
#ifndef HA_CHECKS_H
#define HA_CHECKS_H

#include <stdint.h>

#include "ha_core.h"

/* Reasons that concern the HP command itself (they reset the stable window). */
#define HA_REASONS_COMMAND                                                                       \
  (HA_REASON_NO_COMMAND | HA_REASON_DEADLINE_MISS | HA_REASON_NOT_FINITE |                       \
   HA_REASON_ACTUATOR_REGION | HA_REASON_ALPHA_BETA | HA_REASON_SENSOR_LINK | HA_REASON_FROZEN | \
   HA_REASON_INTEGRITY | HA_REASON_ESTIMATOR | HA_REASON_PULL)

/* Reasons that concern the state the HA judges by: a hand-back needs none of them. */
#define HA_REASONS_STATE \
  (HA_REASON_STALL | HA_REASON_CEILING | HA_REASON_STATE_REGION | HA_REASON_NO_HA_STATE)

/* Reasons that are no fault of the HP: the HA's own sensors, the operator's choice. A switch for
 * these alone neither resets the HP nor counts towards the restart cap. */
#define HA_REASONS_NOT_HP (HA_REASON_NO_HA_STATE | HA_REASON_GROUND_COMMAND)

/* The aircraft state after checking: a component that failed its check is marked not ok and
 * holds a harmless value (the region centre, or 0), never the raw input. */
typedef struct {
  uint8_t attitude_ok; /* roll, pitch, P, Q, R: present, fresh, finite, plausible */
  uint8_t altitude_ok;
  uint8_t position_ok;   /* north, east, heading */
  uint8_t airspeed_ok;   /* the pitot: a reading in range, believed against the INS, fresh */
  uint8_t alpha_beta_ok; /* the HP command's estimates are finite */
  /* Airborne is decided by the core from these, latched (ha_core.c): any one signal of flight
   * sets it, and only a landing evident for landed_confirm_us clears it. */
  uint8_t flying_evidence; /* above stall (pitot), above alt0 (INS), or the INS not parked */
  /* The pitot alive and below stall, and a fresh INS state parked and low. A dead pitot or a
   * stale INS is never evidence of a landing: it cannot tell flying from parked. */
  uint8_t landed_evidence;
  uint8_t still;     /* INS: level, no body rates, no ground speed (self-test gate) */
  uint8_t airborne;  /* set by the core: the latch */
  uint8_t on_ground; /* set by the core: the one rule (HaOutputs.on_ground) */
  uint8_t parked;    /* set by the core: on the ground, still, at a known height: self-test */
  uint8_t stalling;  /* set by the core: STALL raised on a speed_known: fly it out */
  /* The HA's own airspeed picture (ha_airdata.c), whatever the pitot does. */
  uint8_t speed_ok;    /* ias_ftps set: the pitot believed, else the INS (the checks judge by it) */
  uint8_t speed_known; /* ... and an airspeed: the pitot's, or the INS's less a known wind */
  uint8_t near_stall;  /* at or below the 1 g hand-back speed */
  uint8_t alpha_ok;    /* the angle of attack looked at: near the stall, attitude, INS velocity */
  float ias_sq;        /* ias_ftps^2, once per period */
  float ias_ftps;      /* indicated: the stall speed is an indicated one */
  float tas_ftps;      /* true: what the INS sees over the ground, less the wind */
  float climb_ftps;    /* the INS's: with path_tas_sq the flight path, sin(gamma) = climb / TAS */
  float path_tas_sq; /* the INS's velocity less the wind learnt so far, squared: not the pitot's */
  float cos_bank;    /* 1 / load factor of a level turn; 0 at 90 deg of bank and beyond */
  float load_factor; /* lift / weight, from the gyros (ha_airdata.c); 1 without attitude */
  float accel_load_factor; /* the INS's accelerometer's, when fresh; else 0 */
  float lift_load_factor;  /* the larger of the two: the load the wing carries (lift guard) */
  float heading_north;     /* the heading's unit vector (position_ok), for the circle's guidance */
  float heading_east;
  float x[HA_X_DIM];
  float airspeed_ftps;
  float heading_deg;
  float north_ft;
  float east_ft;
} HaStateView;

/* What the core's bookkeeping knows about the HP command this period. */
typedef struct {
  uint8_t have_cmd;       /* a command has ever arrived */
  uint8_t intact;         /* the latest command's CRC matches its fields */
  uint32_t age_us;        /* since the latest arrived */
  uint32_t late_periods;  /* consecutive periods without a new command */
  uint8_t frozen;         /* the latest command repeated its predecessor's seq */
  const HaHpCommand *cmd; /* never NULL; meaningful only when have_cmd */
} HaCmdFacts;

/* cmd is the latest HP command (never NULL); have_cmd says whether one ever arrived; own is
 * the core's tracking of its own sensors (ages, the last good airspeed). */
void ha_state_view(const HaAircraftConfig *cfg, const HaInputs *in, const HaHpCommand *cmd,
                   int have_cmd, const HaOwnSensors *own, HaStateView *out);

/* Runs every check; returns the HA_REASON_* bits and the two region values. */
uint32_t ha_checks_evaluate(const HaAircraftConfig *cfg, const HaCmdFacts *facts,
                            const HaStateView *state, float *state_region_max,
                            float *actuator_region_max);

#endif /* HA_CHECKS_H */
