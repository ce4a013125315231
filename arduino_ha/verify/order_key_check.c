/* The witness for the HaOrderKey axioms that make prove-ha assumes (src/core/ha_num.h): checks
 * ha_order_key against the host's IEEE-754 float for every one of the 2^32 bit patterns. A
 * function that satisfies the axioms exists (this one), so they are consistent: WP cannot prove
 * a falsehood from them. Run by make prove-ha before WP.
 *  - key_finite, key_nan: for each pattern, finite and NaN exactly at the key ranges they name.
 *  - key_orders: from +0 up to +inf each next pattern is the next larger float and its key is
 *    one more; from -0 down to -inf the next pattern is the next smaller float and its key one
 *    less; -0 and +0 are equal, key 0 both. So along the floats that are not NaN, in the order
 *    of their values, the keys count up by one and stay put only across -0 == +0: key(a) <=
 *    key(b) exactly when a <= b. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "ha_num.h"

static float of_bits(uint32_t bits) {
  float v;
  memcpy(&v, &bits, sizeof v);
  return v;
}

int main(void) {
  uint64_t failures = 0, patterns = 0;
  for (uint64_t u = 0; u <= 0xFFFFFFFFu; ++u) {
    const uint32_t bits = (uint32_t)u;
    const float a = of_bits(bits);
    const int32_t key = ha_order_key(a);
    const int finite = isfinite(a) != 0, nan = isnan(a) != 0;
    ++patterns;
    if (finite != (key > -HA_KEY_INF && key < HA_KEY_INF) ||
        nan != (key > HA_KEY_INF || key < -HA_KEY_INF)) {
      if (++failures <= 10)
        printf("order_key_check: 0x%08x: key %d (finite %d, NaN %d)\n", (unsigned)bits, (int)key,
               finite, nan);
    }
    if ((bits & 0x7FFFFFFFu) <
        0x7F800000u) { /* a finite float: the next pattern is its neighbour */
      const float b = of_bits(bits + 1u);
      const int32_t next = ha_order_key(b);
      const int up = (bits & 0x80000000u) == 0u;
      if (up ? !(b > a && next == key + 1) : !(b < a && next == key - 1)) {
        if (++failures <= 10)
          printf("order_key_check: 0x%08x -> next: keys %d, %d\n", (unsigned)bits, (int)key,
                 (int)next);
      }
    }
  }
  if (!(of_bits(0x80000000u) == of_bits(0u) && ha_order_key(of_bits(0x80000000u)) == 0 &&
        ha_order_key(0.0f) == 0)) {
    ++failures;
    printf("order_key_check: -0 and +0 do not meet at key 0\n");
  }
  printf("order_key_check: %llu bit patterns, %llu failures\n", (unsigned long long)patterns,
         (unsigned long long)failures);
  return failures == 0u ? 0 : 1;
}
