/* The one policy: flags and state in, the controller that drives the servos out. */
#ifndef HA_POLICY_H
#define HA_POLICY_H

#include <stdint.h>

typedef struct {
  uint8_t controller;          /* HA_CONTROLLER_* now */
  uint8_t manual;              /* RC alive and the PIC/CIC switch at PIC */
  uint8_t latched;             /* the restart cap was reached before */
  uint8_t self_test;           /* the pre-flight self-test is running */
  uint8_t ground_command;      /* the operator selected the HA */
  uint32_t reasons;            /* HA_REASON_* failing this period */
  uint8_t stable;              /* the HP command has been valid for the stable window */
  uint8_t inner;               /* inside the inner region, no state reason, airspeed margin */
  uint8_t restart_cap_reached; /* K restarts already within T */
  uint8_t boot_overdue;        /* reset, released, and no valid command within the boot timeout */
  uint8_t hp_failed;        /* it had been up, and now fails a command check, no reset under way */
  uint8_t operator_restart; /* the operator's RESTART_HP was accepted this period */
} HaPolicyIn;

uint8_t ha_policy_decide(const HaPolicyIn *p);

/* Whether to pulse the HP reset line this period, given the controller ha_policy_decide chose:
 * one decision, so one pulse counts once toward the cap whatever asked for it. */
uint8_t ha_policy_restart(const HaPolicyIn *p, uint8_t next);

#endif /* HA_POLICY_H */
