#include "ha_policy.h"

#include "ha_checks.h"
#include "ha_core.h"

uint8_t ha_policy_decide(const HaPolicyIn *p) {
  const int on_hp = p->controller == HA_CONTROLLER_HP;
  const int recovering = p->controller == HA_CONTROLLER_RECOVERING;
  const int any_bad = p->reasons != 0u;
  const int hp_bad = (p->reasons & ~HA_REASONS_NOT_HP) != 0u;
  const int cmd_bad = (p->reasons & HA_REASONS_COMMAND) != 0u;
  const int cap = p->restart_cap_reached != 0u;
  /* One rule per line, most severe first; the first rule that matches decides. */
  if (p->manual) return HA_CONTROLLER_MANUAL;                        /* the pilot, always */
  if (p->latched) return HA_CONTROLLER_HA_LATCHED;                   /* cap reached: for good */
  if (p->self_test) return HA_CONTROLLER_HA;                         /* on the ground, asked for */
  if (p->ground_command) return HA_CONTROLLER_HA;                    /* operator chose the HA */
  if (p->boot_overdue && cap) return HA_CONTROLLER_HA_LATCHED;       /* reset K times, never back */
  if (on_hp && hp_bad && cap) return HA_CONTROLLER_HA_LATCHED;       /* one HP failure too many */
  if (on_hp && any_bad) return HA_CONTROLLER_HA;                     /* any failed check */
  if (on_hp) return HA_CONTROLLER_HP;                                /* every check holds */
  if (recovering && cmd_bad && cap) return HA_CONTROLLER_HA_LATCHED; /* failed recovery */
  if (cmd_bad) return HA_CONTROLLER_HA;                              /* HP not valid (yet) */
  if (p->stable && p->inner) return HA_CONTROLLER_HP;                /* stable, well inside */
  return HA_CONTROLLER_RECOVERING;                                   /* watched, not used */
}

/* One rule per line as above. The HP is restarted whoever flies (the pilot and the operator's HA
 * keep the servos); the HA's own sensor faults and the operator's choice are no HP failure. */
uint8_t ha_policy_restart(const HaPolicyIn *p, uint8_t next) {
  const int leaving_hp =
      (p->controller == HA_CONTROLLER_HP || p->controller == HA_CONTROLLER_RECOVERING) &&
      next == HA_CONTROLLER_HA;
  const int hp_fault =
      (p->reasons & ~HA_REASONS_NOT_HP) != 0u && !p->ground_command && !p->self_test;
  if (p->latched || next == HA_CONTROLLER_HA_LATCHED) return 0u; /* for good: nothing to gain */
  if (p->operator_restart) return 1u;    /* asked for (refused while the HP flies) */
  if (leaving_hp && hp_fault) return 1u; /* the HP failed a check */
  if (p->restart_cap_reached) return 0u; /* K within T: no more of our own */
  if (p->boot_overdue) return 1u;        /* reset, and not back in time */
  if (p->hp_failed) return 1u;           /* it failed while someone else flew */
  return 0u;
}
