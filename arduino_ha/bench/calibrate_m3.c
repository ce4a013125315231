/* Checks the instruction-counting method before the benchmark trusts it: a loop of exactly
 * 2 instructions per iteration (subs + taken bne) must read back as 2 * n instructions, within
 * one timer tick, for several n. Exits QEMU with failure if not. */
#include <stdint.h>

#include "insn_timer.h"
#include "semihost.h"

static void spin(uint32_t n) {
  __asm__ volatile(
      "1: subs %0, %0, #1\n"
      "   bne 1b\n"
      : "+r"(n)
      :
      : "cc");
}

static uint32_t measure_ticks(uint32_t n) {
  const uint32_t t0 = ha_insn_timer_read();
  spin(n);
  return t0 - ha_insn_timer_read();
}

int main(void) {
  static const uint32_t loops[] = {1000u, 1013u, 7777u, 20000u, 100000u};
  uint32_t overhead;
  int ok = 1;
  uint32_t i;
  ha_insn_timer_start();
  overhead = measure_ticks(1u);
  for (i = 0u; i < sizeof loops / sizeof loops[0]; ++i) {
    const uint32_t measured = (measure_ticks(loops[i]) - overhead) * HA_INSN_PER_TICK;
    const uint32_t expected = 2u * loops[i];
    const uint32_t err = measured > expected ? measured - expected : expected - measured;
    char line[96] = "calibration: loop ";
    ha_append_u32(line, sizeof line, expected);
    ha_append_str(line, sizeof line, " insns measured ");
    ha_append_u32(line, sizeof line, measured);
    ha_append_str(line, sizeof line, "\n");
    ha_semihost_write0(line);
    if (err > HA_INSN_PER_TICK) {
      ok = 0;
    }
  }
  return ok ? 0 : 1;
}
