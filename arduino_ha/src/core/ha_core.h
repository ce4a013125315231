/* The HA core: one call per control period decides who drives the servos (HP, HA safety
 * controller, or the pilot) and what goes to them. Pure: time and inputs in, outputs out; no
 * board access, no heap, no recursion. CONTROLLER_* and REASON_* are generated from
 * msg/DecisionStatus.msg (ha_decision_status.h), HA_OP_* from msg/OperatorCommand.msg
 * (ha_operator_command.h; SET_HOME is the INS adapter's, ha_ins_set_home, not the core's). */
#ifndef HA_CORE_H
#define HA_CORE_H

#include <stdint.h>

#include "../generated/ha_config.h"
#include "../generated/ha_decision_status.h"
#include "../generated/ha_operator_command.h"
#include "ha_types.h"
#include "hp_command.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
  /* Aircraft state. Airspeed is the HA's own pitot; attitude, rates, altitude and position come
   * from the INS through the link and carry their arrival time. Anything NaN/inf/out of range or
   * stale fails the state checks; the core never uses it unchecked. */
  float airspeed_ftps;
  float roll_deg;    /* right wing down positive */
  float pitch_deg;   /* nose up positive */
  float heading_deg; /* true, clockwise from north, any wrap */
  float p_deg_s;     /* body roll rate */
  float q_deg_s;     /* body pitch rate */
  float r_deg_s;     /* body yaw rate, nose right positive */
  float altitude_agl_ft;
  float north_ft; /* position relative to the home/rally point the HA circles */
  float east_ft;
  float groundspeed_ftps; /* horizontal speed over the ground (INS) */
  /* The INS's velocity and height, for the HA's airspeed picture (ha_airdata.c): the wind is what
   * the pitot and the velocity over the ground disagree by, the flight path is the climb over
   * the speed, the air's density follows from the height above sea level. */
  float vel_north_ftps;
  float vel_east_ftps;
  float climb_ftps; /* vertical speed, up positive */
  /* The INS's accelerometer along the body's z axis, as a load factor (lift / weight: 1 in level
   * flight), when its packet carries one (accel_ok); a gust's load shows here and not in the
   * gyros. */
  float accel_load_factor;
  uint8_t accel_ok;
  float
      altitude_msl_ft; /* above sea level (the WGS84 ellipsoid: the geoid's 100 m do not matter) */
  uint8_t on_ground;   /* 1: weight on wheels / landed as reported by the INS side */
  uint8_t state_valid; /* 0 until the link has delivered a state at least once */
  /* 1: the state carries attitude, rates, groundspeed and on_ground but no home yet, so no
   * altitude AGL and no position (the INS adapter before its first home: ha_ins.h). */
  uint8_t home_unknown;
  uint32_t state_rx_us; /* when that state arrived */

  HaRcInputs rc;

  /* The latest HP command (alpha/beta estimates are its alpha_est_deg/beta_est_deg). The link
   * increments hp_cmd_count on every command it delivers; 0 means none yet. */
  HaHpCommand hp_cmd;
  uint32_t hp_cmd_count;
  uint32_t hp_cmd_rx_us;

  /* The operator's request for this period, HA_OP_*, HA_OP_NONE for none: the firmware queues
   * what the link delivers and hands over one a period, oldest first (ha_app.c), so each sees
   * what the one before it did. SET_HOME is the INS adapter's, never the core's. */
  uint8_t operator_command;
} HaInputs;

typedef struct {
  HaSurfaces surfaces; /* what goes to the servos: always finite and inside S_u */
  /* The safety controller's own command this period, whoever flies (before any rate limit):
   * what the HA would fly if it took over now. Reported, never driven from here. */
  HaSurfaces ha_command;
  uint8_t controller; /* HA_CONTROLLER_* */
  uint32_t reasons;   /* HA_REASON_* failing this period */
  uint32_t reasons_at_switch;
  uint16_t restart_count;
  uint8_t restart_requested; /* 1 in the period a restart is requested (send it to the HP side) */
  uint8_t hp_reset_asserted; /* level for the HP reset line */
  uint32_t last_seq;
  float stable_for_s;
  /* Checked values (NaN never leaves the core: unchecked values are reported as 0). */
  float airspeed_ftps;
  float altitude_agl_ft;
  float alpha_deg;
  float beta_deg;
  float state_region_max;    /* max_i (S_x (x - x0))_i */
  float actuator_region_max; /* max_i (S_u (u - u0))_i of the HP command */
  /* The one "on the ground" verdict of this period (ha_core.c, decide_airborne): the airborne
   * latch clear, the pitot alive and below stall, and a fresh INS state parked and low. The INS
   * adapter takes its first home and accepts SET_HOME only on it (ha_ins.h). */
  uint8_t on_ground;
  uint8_t self_test_active;
  uint8_t operator_accepted; /* this period's operator_command was executed */
} HaOutputs;

/* Cascaded-PID safety controller memory. */
typedef struct {
  float roll_integ_deg;
  float pitch_integ_deg;
  float throttle_integ;
} HaSafetyCtrlState;

/* The HA's own sensors as tracked across periods. Ages saturate, so a state that stopped
 * arriving never looks fresh again when the 32-bit clock wraps; a failed pitot read holds the
 * last good reading for up to airspeed_timeout_us (one glitch is not a dead sensor). */
typedef struct {
  uint32_t state_age_us;    /* since the INS state arrived; UINT32_MAX before the first */
  float airspeed_ftps;      /* the last reading inside [0, max_airspeed_ftps] */
  uint32_t airspeed_age_us; /* since that reading; UINT32_MAX before the first */
} HaOwnSensors;

/* The INS's velocity as the HA uses it: checked plausible and clamped, once per period. */
typedef struct {
  float north_ftps, east_ftps, climb_ftps;
} HaVelocity;

/* The HA's airspeed picture across periods (ha_airdata.c): a wind learnt from the pitot against
 * the INS, slowly, and the air's density where it was last computed. */
typedef struct {
  float wind_north_ftps; /* where the air moves to, |wind| <= max_wind_ftps */
  float wind_east_ftps;
  uint32_t wind_learned_us;  /* learnt this long from a believed pitot (saturating) */
  uint32_t pitot_doubted_us; /* since the pitot was last believed (saturating) */
  float density_below_ft;    /* tas_per_ias holds between these heights: its own +/- 100 ft */
  float density_above_ft;
  float tas_per_ias; /* sqrt(rho0 / rho): true airspeed per indicated */
  float ias_per_tas;
  float heading_north; /* the heading's unit vector, computed once per period */
  float heading_east;
  HaVelocity velocity; /* this period's, when velocity_ok */
  uint8_t velocity_ok;
  /* The pitot's last reading and how long it has read exactly that: a live sensor's noise moves
   * its last bits every read, an iced or frozen one does not (saturating). */
  float last_reading_ftps;
  uint32_t same_reading_us;
} HaAirdata;

typedef struct {
  uint8_t active;
  uint32_t step;
  uint32_t step_started_us;
} HaSelfTestState;

typedef struct {
  const HaAircraftConfig *cfg;
  uint8_t controller;     /* HA_CONTROLLER_* */
  uint8_t latched;        /* the restart cap was reached: HA for good */
  uint8_t ground_command; /* the operator selected the HA */
  uint32_t reasons_at_switch;
  uint8_t have_step; /* 0 before the first step */
  uint32_t last_step_us;
  /* HP command bookkeeping */
  uint32_t seen_cmd_count;
  uint8_t have_cmd; /* some command arrived, intact or not */
  uint8_t have_seq; /* last_seq is that of an intact command */
  uint8_t frozen;
  uint32_t last_seq;
  uint32_t late_periods;
  uint32_t cmd_age_us;
  uint32_t stable_for_us;    /* the command has been valid this long (saturating) */
  uint32_t own_state_for_us; /* the HA's own state has been whole this long (saturating) */
  /* The HA's own sensors across periods */
  uint32_t seen_state_rx_us;
  HaOwnSensors own;
  HaAirdata airdata;
  /* Airborne, latched once flying until a landing has been evident for landed_confirm_us. */
  uint8_t airborne;
  uint32_t landed_for_us;
  /* restarts */
  uint16_t restart_count;
  uint32_t restart_times_us[HA_MAX_RESTARTS_CAP];
  uint32_t restart_history_len;
  uint8_t reset_active;
  uint32_t reset_started_us;
  uint32_t reset_released_us;
  uint8_t awaiting_boot; /* reset, and no valid command since */
  uint8_t hp_up;         /* a wholly valid command since power-up or the last reset */
  /* bumpless transfer */
  HaSurfaces applied; /* what went to the servos last period */
  uint8_t transition_active;
  uint8_t last_source;
  HaSafetyCtrlState sc;
  HaSelfTestState self_test;
} HaCore;

/* cfg must outlive core (it is the generated const). A core that has not been stepped drives
 * nothing; the first step starts in HA_CONTROLLER_HA. */
void ha_core_init(HaCore *core, const HaAircraftConfig *cfg);

/* After a reset of the HA in flight (ha_app_restore, ha_retained.h): the airborne latch, the
 * restart cap's latch and the operator's HA selection as they were before it. Call after
 * ha_core_init, before the first step. */
void ha_core_restore(HaCore *core, uint8_t airborne, uint8_t latched, uint8_t ground_command);

/* One control period at now_us (free-running, wrapping microsecond clock). */
void ha_core_step(HaCore *core, const HaInputs *in, uint32_t now_us, HaOutputs *out);

#ifdef __cplusplus
}
#endif

#endif /* HA_CORE_H */
