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
  if (p->manual) return HA_CONTROLLER_MANUAL;                     /* the pilot, always */
  if (p->latched) return HA_CONTROLLER_HA_LATCHED;                /* cap reached: for good */
  if (p->self_test) return HA_CONTROLLER_HA;                      /* on the ground, asked for */
  if (p->ground_command) return HA_CONTROLLER_HA;                 /* operator chose the HA */
  if (p->boot_overdue && cap) return HA_CONTROLLER_HA_LATCHED;    /* reset K times, never back */
  if (on_hp && hp_bad && cap) return HA_CONTROLLER_HA_LATCHED;    /* one HP failure too many */
  if (on_hp && any_bad) return HA_CONTROLLER_HA;                  /* any failed check */
  if (on_hp) return HA_CONTROLLER_HP;                             /* every check holds */
  if (recovering && cmd_bad && cap) return HA_CONTROLLER_HA_LATCHED; /* failed recovery */
  if (cmd_bad) return HA_CONTROLLER_HA;                           /* HP not valid (yet) */
  if (p->stable && p->inner) return HA_CONTROLLER_HP;             /* stable, well inside */
  return HA_CONTROLLER_RECOVERING;                                /* watched, not used */
}

/* An HP reset for a failure that has not come back gets another reset; the operator's HA and the
 * self-test are no HP failure, and at the cap ha_policy_decide has latched instead. */
uint8_t ha_policy_reset_again(const HaPolicyIn *p, uint8_t next) {
  return (uint8_t)(next == HA_CONTROLLER_HA && p->boot_overdue && !p->ground_command &&
                   !p->self_test);
}
