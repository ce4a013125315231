/* Negative control for make verify-ha-eva (tools/eva.sh --negative): a deliberately wrong "core"
 * that the same checks must flag, so a broken analysis setup (no alarms because nothing was
 * analysed, or the alarm counter reading the wrong lines) cannot pass silently. Two planted
 * defects:
 *  - a clamp written with comparisons that NaN slips through (caught as an unproven servo
 *    assertion in the any-bits mode);
 *  - a square of a huge finite input (caught as an overflow-to-inf alarm in the finite mode). */
#include <float.h>

#include "__fc_builtin.h"

static float clamp_lets_nan_through(float x, float lim) {
  return x > lim ? lim : (x < -lim ? -lim : x);
}

int main(void) {
  float in;
#ifdef HA_EVA_ANY_BITS
  Frama_C_make_unknown((char *)&in, sizeof in);
#else
  in = Frama_C_float_interval(-FLT_MAX, FLT_MAX);
#endif
  {
    const float servo = clamp_lets_nan_through(in, 15.0f);
    const float energy = in * in;
    /*@ assert servo_finite: \is_finite(servo); */
    /*@ assert servo_in_su: -15.0f <= servo <= 15.0f; */
    return energy > 1.0f;
  }
}
