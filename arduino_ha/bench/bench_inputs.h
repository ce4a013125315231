/* Deterministic input timeline for the HA step benchmarks (QEMU Cortex-M3 and host). Every
 * period gets a plausible flight state and HP command, and the timeline cycles through the
 * situations that exercise every path of the core: HP in control, HP silent, late commands,
 * NaN/inf/huge/denormal fields, commands outside S_u, stall, above the ceiling, state outside S_x,
 * frozen sequence numbers, corrupt CRCs, the pilot's switch, and recovery back to the HP. Same
 * seed, same inputs, on both machines. */
#ifndef HA_BENCH_INPUTS_H
#define HA_BENCH_INPUTS_H

#include <stdint.h>

#include "ha_core.h"

typedef struct {
  uint32_t rng;
  uint32_t period;
  uint32_t now_us;
  uint32_t seq;
  const HaAircraftConfig *cfg;
} HaBenchTimeline;

void ha_bench_timeline_init(HaBenchTimeline *t, const HaAircraftConfig *cfg, uint32_t seed);

/* Writes the inputs of the next period into *in (which keeps the link's counters between calls)
 * and returns that period's time in microseconds. */
uint32_t ha_bench_timeline_next(HaBenchTimeline *t, HaInputs *in);

#endif
