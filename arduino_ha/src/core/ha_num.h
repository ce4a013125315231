/* Numeric guards for the core. Finiteness is decided from the IEEE-754 bits, so a NaN or an
 * infinity is rejected without ever entering a floating-point operation. */
#ifndef HA_NUM_H
#define HA_NUM_H

#include <stdint.h>
#include <string.h>

/* For the bit-level helpers, a dozen integer instructions each: at -Os gcc called them out of
 * line, and the calls cost 600 of the worst step's instructions on the Cortex-M3. Unoptimised
 * builds (the coverage build's -O0) keep them functions, so that their branches are counted
 * once, in this file, not again in every caller. */
#if defined(__OPTIMIZE__)
#define HA_BITS_INLINE static inline __attribute__((always_inline))
#else
#define HA_BITS_INLINE static inline
#endif

HA_BITS_INLINE int ha_finite(float v) {
  uint32_t bits;
  memcpy(&bits, &v, sizeof bits);
  return (bits & 0x7F800000u) != 0x7F800000u;
}

/* The IEEE-754 bits as an integer that orders like the value: -0 and +0 meet at 0, infinities
 * lie beyond every finite value and NaNs beyond the infinities. WP takes that as three axioms
 * (make prove-ha cannot follow memcpy into the bits); verify/order_key_check.c checks them for
 * every one of the 2^32 floats before each proof, which also shows they are consistent. */
#define HA_KEY_INF 0x7F800000 /* the key of +inf; -HA_KEY_INF is -inf's */
#ifdef HA_WP
/*@ axiomatic HaOrderKey {
  @   logic integer ha_key(float v);
  @   axiom key_orders: \forall float a, b; !\is_NaN(a) && !\is_NaN(b) ==>
  @     (ha_key(a) <= ha_key(b) <==> \le_float(a, b));
  @   axiom key_finite: \forall float a;
  @     \is_finite(a) <==> -HA_KEY_INF < ha_key(a) < HA_KEY_INF;
  @   axiom key_nan: \forall float a;
  @     \is_NaN(a) <==> (ha_key(a) > HA_KEY_INF || ha_key(a) < -HA_KEY_INF);
  @ }
  @ */
/*@ assigns \nothing;
  @ ensures order_key: \result == ha_key(v);
  @ */
#endif
HA_BITS_INLINE int32_t ha_order_key(float v) {
  uint32_t bits;
  memcpy(&bits, &v, sizeof bits);
  return (bits & 0x80000000u) != 0u ? -(int32_t)(bits & 0x7FFFFFFFu) : (int32_t)bits;
}

/* Same verdict as a > b for operands that are not NaN (a verdict only, as for ha_in_range).
 * Used on values already checked or clamped, where the core compares most. */
HA_BITS_INLINE int ha_greater(float a, float b) { return ha_order_key(a) > ha_order_key(b); }

/* Same verdict as lo <= v <= hi for finite bounds lo <= hi, so NaN and inf fail; decided on the
 * bits, since on the FPU-less Due each float compare is a library call of some 35 instructions.
 * A verdict only: static analysis cannot carry it over to v, so a value that goes on into
 * arithmetic is passed through ha_clampf. */
HA_BITS_INLINE int ha_in_range(float v, float lo, float hi) {
  const int32_t key = ha_order_key(v);
  return key >= ha_order_key(lo) && key <= ha_order_key(hi);
}

/* Same verdict as ha_in_range(v, -span, span) for a finite span >= 0, decided on the IEEE-754
 * bits: for non-negative floats the bit patterns order like the values, and NaN and inf lie
 * above every finite span. Integer work only: on the FPU-less Due each float compare is a
 * library call of some 40 instructions. */
HA_BITS_INLINE int ha_within_span(float v, float span) {
  uint32_t v_bits, span_bits;
  memcpy(&v_bits, &v, sizeof v_bits);
  memcpy(&span_bits, &span, sizeof span_bits);
  return (v_bits & 0x7FFFFFFFu) <= (span_bits & 0x7FFFFFFFu);
}

/* Frama-C's view (EVA and WP alike, src/core/README.md "Proofs"). */
#ifdef __FRAMAC__
/*@ predicate ha_within(float v, float lo, float hi) =
  @   \is_finite(v) && \le_float(lo, v) && \le_float(v, hi);
  @ */
#endif
#ifdef HA_WP
/*@ axiomatic HaFloat {
  @   // IEEE-754 negation (exact): verify/ha_wp.driver maps it onto WP's own, so a float bound
  @   // can be negated without leaving the float model for the reals.
  @   logic float ha_neg(float x);
  @ }
  @ */
#endif

/* Into [lo, hi]; NaN becomes the in-range value nearest zero, +/-inf the nearer bound. Decided
 * on the order keys: integer compares, where each float compare is a library call of some 35
 * instructions on the FPU-less Due (two a call, 31 calls: 2,600 of the worst step's 14,720).
 * WP proves the contract from the keys' axioms (ha_num.c); EVA takes the proved contract in
 * place of the body (-eva-use-spec), which gives it the bound whatever bits v holds. */
#ifdef __FRAMAC__
/*@ requires bounds: \is_finite(lo) && \is_finite(hi) && \le_float(lo, hi);
  @ assigns \result \from v, lo, hi;
  @ ensures clamp_in_bounds: ha_within(\result, lo, hi);
  @ ensures clamp_keeps_in_range: ha_within(v, lo, hi) ==> \eq_float(\result, v);
  @ ensures clamp_nan_nearest_zero: \is_NaN(v) &&
  @   \le_float(lo, (float)0.0) && \le_float((float)0.0, hi) ==> \eq_float(\result, (float)0.0);
  @ */
#endif
float ha_clampf(float v, float lo, float hi);

/* Microseconds from then to now on the wrapping 32-bit clock. */
#ifdef HA_WP
/*@ // The difference modulo 2^32, as the wrapping clock gives it.
  @ logic integer ha_elapsed(integer now, integer then) = (uint32_t)(now - then);
  @ */
/*@ assigns \nothing;
  @ ensures elapsed_wraps: \result == ha_elapsed(now_us, then_us);
  @ */
#endif
static inline uint32_t ha_elapsed_us(uint32_t now_us, uint32_t then_us) { return now_us - then_us; }

/* a + b, stuck at UINT32_MAX: an age or a window that saturates never looks young again. */
static inline uint32_t ha_add_sat(uint32_t a, uint32_t b) {
  return a > UINT32_MAX - b ? UINT32_MAX : a + b;
}

#endif /* HA_NUM_H */
