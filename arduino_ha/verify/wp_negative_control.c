/* Negative control for make prove-ha (tools/wp.sh --negative): deliberately wrong code under the
 * core's own predicates, which WP must NOT prove with the same models, provers and driver, so a
 * broken setup (contracts not read, a driver that makes everything true, goals never sent to a
 * prover) cannot pass silently. Each planted_* contract is false:
 *  - a clamp written with comparisons that NaN slips through (the float model must see NaN);
 *  - a clamp on the order keys that forgets NaN's keys lie past both ends (the keys' axioms
 *    must not prove what the keys do not give);
 *  - a hand-back to the HP that forgets the state reasons (the bit reasoning must be real);
 *  - a history that forgets the restart it was asked to record (the frame must be real). */
#include <stdint.h>

#include "ha_checks.h"
#include "ha_num.h"

/*@ requires \is_finite(lo) && \is_finite(hi) && \le_float(lo, hi);
  @ assigns \nothing;
  @ ensures planted_nan_through: ha_within(\result, lo, hi);
  @ */
float clamp_lets_nan_through(float v, float lo, float hi) {
  return v > hi ? hi : (v < lo ? lo : v);
}

/*@ requires \is_finite(lo) && \is_finite(hi) && \le_float(lo, hi);
  @ assigns \nothing;
  @ ensures planted_keyed_nan_to_zero: \is_NaN(v) &&
  @   \le_float(lo, (float)0.0) && \le_float((float)0.0, hi) ==> \eq_float(\result, (float)0.0);
  @ */
float keyed_clamp_forgetting_nan(float v, float lo, float hi) {
  const int32_t key = ha_order_key(v);
  if (key < ha_order_key(lo)) return lo;
  return key > ha_order_key(hi) ? hi : v;
}

/*@ assigns \nothing;
  @ ensures planted_handback_on_state_reason: \result == HA_CONTROLLER_HP ==>
  @   (reasons & HA_REASONS_COMMAND) == 0 && (reasons & HA_REASONS_STATE) == 0;
  @ */
uint8_t handback_forgetting_state(uint32_t reasons, uint8_t stable) {
  if ((reasons & HA_REASONS_COMMAND) != 0u) return HA_CONTROLLER_HA;
  return stable ? HA_CONTROLLER_HP : HA_CONTROLLER_RECOVERING;
}

typedef struct {
  uint32_t times_us[4];
  uint32_t len;
} History;

/*@ requires \valid(h) && h->len < 4;
  @ assigns h->times_us[0 .. 3], h->len;
  @ ensures planted_history_overflow:
  @   h->len == \old(h->len) + 1 && h->times_us[\old(h->len)] == now_us;
  @ */
void record_forgetting(History *h, uint32_t now_us) { h->times_us[h->len] = now_us; }
