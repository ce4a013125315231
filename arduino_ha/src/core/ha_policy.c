#include "ha_policy.h"

#include "ha_checks.h"
#include "ha_core.h"

/* The rules a reviewer names, proved by make prove-ha (Frama-C WP; README.md, "Proofs") for
 * every input. The requires are what the core's step promises the policy: inner is never set
 * with a state reason, and the operator's choice is a reason. Every reason bit is a command, a
 * state or the operator's reason (ha_checks.h), so ha_no_reason is reasons == 0. */
#ifdef HA_WP
/*@ predicate ha_no_reason(integer r) = (r & HA_REASONS_COMMAND) == 0 &&
  @   (r & HA_REASONS_STATE) == 0 && (r & HA_REASON_GROUND_COMMAND) == 0;
  @ // The reasons the HP is to blame for, as the C code computes them (32-bit complement).
  @ logic integer ha_hp_reasons(integer r) = r & (uint32_t)~HA_REASONS_NOT_HP;
  @ predicate ha_takeover(HaPolicyIn *p) =
  @   p->manual != 0 || p->latched != 0 || p->self_test != 0 || p->ground_command != 0;
  @ // The HP (flying or recovering) failing a check it is to blame for, or its boot overdue.
  @ predicate ha_hp_failure(HaPolicyIn *p) =
  @   (p->controller == HA_CONTROLLER_HP && ha_hp_reasons(p->reasons) != 0) ||
  @   (p->controller == HA_CONTROLLER_RECOVERING && (p->reasons & HA_REASONS_COMMAND) != 0) ||
  @   p->boot_overdue != 0;
  @ // At the restart cap the HP side loses the servos to the (unlatched) HA only when it is not
  @ // to blame: the operator's choice, the self-test, the HA's own sensors.
  @ predicate ha_cap_spares_only_blameless(HaPolicyIn *p, integer next) =
  @   p->restart_cap_reached != 0 && next == HA_CONTROLLER_HA &&
  @   (p->controller == HA_CONTROLLER_HP || p->controller == HA_CONTROLLER_RECOVERING) ==>
  @     p->self_test != 0 || p->ground_command != 0 || ha_hp_reasons(p->reasons) == 0;
  @ */
/*@ requires \valid_read(p);
  @ requires inner_without_state_reason: p->inner != 0 ==> (p->reasons & HA_REASONS_STATE) == 0;
  @ requires operator_choice_is_a_reason:
  @   (p->reasons & HA_REASON_GROUND_COMMAND) != 0 ==> p->ground_command != 0;
  @ assigns \nothing;
  @ ensures total_one_controller: \result == HA_CONTROLLER_HP || \result == HA_CONTROLLER_HA ||
  @   \result == HA_CONTROLLER_RECOVERING || \result == HA_CONTROLLER_HA_LATCHED ||
  @   \result == HA_CONTROLLER_MANUAL;
  @ ensures pilot_always_and_only: \result == HA_CONTROLLER_MANUAL <==> p->manual != 0;
  @ ensures hp_only_when_every_check_clear: \result == HA_CONTROLLER_HP ==>
  @   ha_no_reason(p->reasons) && !ha_takeover(p);
  @ ensures handback_needs_stable_and_inner: \result == HA_CONTROLLER_HP &&
  @   p->controller != HA_CONTROLLER_HP ==> p->stable != 0 && p->inner != 0;
  @ ensures failing_check_takes_hp_out: p->controller == HA_CONTROLLER_HP && p->reasons != 0 ==>
  @   \result != HA_CONTROLLER_HP;
  @ ensures ha_explained: \result == HA_CONTROLLER_HA ==>
  @   p->self_test != 0 || p->ground_command != 0 || p->reasons != 0;
  @ ensures recovering_explained: \result == HA_CONTROLLER_RECOVERING ==>
  @   p->controller != HA_CONTROLLER_HP && (p->reasons & HA_REASONS_COMMAND) == 0 &&
  @   !(p->stable != 0 && p->inner != 0);
  @ ensures latched_explained: \result == HA_CONTROLLER_HA_LATCHED ==>
  @   p->latched != 0 || p->restart_cap_reached != 0;
  @ ensures latch_is_for_good: p->latched != 0 && p->manual == 0 ==>
  @   \result == HA_CONTROLLER_HA_LATCHED;
  @ ensures hp_failure_at_cap_latches: p->restart_cap_reached != 0 && ha_hp_failure(p) &&
  @   p->manual == 0 && p->self_test == 0 && p->ground_command == 0 ==>
  @   \result == HA_CONTROLLER_HA_LATCHED;
  @ ensures cap_spares_only_blameless: ha_cap_spares_only_blameless(p, \result);
  @ */
#endif
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
#ifdef HA_WP
/*@ requires \valid_read(p);
  @ requires next_from_policy: ha_cap_spares_only_blameless(p, next);
  @ assigns \nothing;
  @ ensures one_pulse_or_none: \result == 0 || \result == 1;
  @ ensures none_once_latched: p->latched != 0 || next == HA_CONTROLLER_HA_LATCHED ==> \result == 0;
  @ ensures at_cap_only_the_operator: p->restart_cap_reached != 0 && \result != 0 ==>
  @   p->operator_restart != 0;
  @ */
#endif
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
