/* Generated from msg/DecisionStatus.msg by tools/gen_decision_status.py: edit the message,
 * then run `make due-sketch-msgs`. */
#ifndef HA_DECISION_STATUS_H
#define HA_DECISION_STATUS_H

/* who drives the servos (DecisionStatus.controller) */
enum {
  HA_CONTROLLER_HP = 0,
  HA_CONTROLLER_HA = 1,
  HA_CONTROLLER_RECOVERING = 2,
  HA_CONTROLLER_HA_LATCHED = 3,
  HA_CONTROLLER_MANUAL = 4
};

/* one bit per failed check (DecisionStatus.reasons) */
#define HA_REASON_NO_COMMAND      1u
#define HA_REASON_DEADLINE_MISS   2u
#define HA_REASON_NOT_FINITE      4u
#define HA_REASON_ACTUATOR_REGION 8u
#define HA_REASON_ALPHA_BETA      16u
#define HA_REASON_SENSOR_LINK     32u
#define HA_REASON_STALL           64u
#define HA_REASON_CEILING         128u
#define HA_REASON_STATE_REGION    256u
#define HA_REASON_FROZEN          512u
#define HA_REASON_INTEGRITY       1024u
#define HA_REASON_ESTIMATOR       2048u
#define HA_REASON_GROUND_COMMAND  4096u
#define HA_REASON_NO_HA_STATE     8192u
#define HA_REASON_PULL            16384u

#endif
