/* ns per HA control step on the host: the benchmark timeline (bench_inputs.c) is generated up
 * front, then RUNS times a fresh core steps through all of it; each run's time per step is
 * recorded and the median (and min/max) reported. */
#define _POSIX_C_SOURCE 199309L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "bench_inputs.h"
#include "ha_aircraft.h"
#include "ha_core.h"

#define STEPS 4000u
#define RUNS 101u

static HaInputs inputs[STEPS];
static uint32_t times_us[STEPS];
static double ns_per_step[RUNS];

static int cmp_double(const void *a, const void *b) {
  const double x = *(const double *)a;
  const double y = *(const double *)b;
  return (x > y) - (x < y);
}

static double now_ns(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

int main(void) {
  static HaCore core;
  HaOutputs out;
  HaBenchTimeline timeline;
  HaInputs in = {0};
  volatile uint32_t sink = 0u;
  uint32_t run;
  uint32_t i;

  ha_bench_timeline_init(&timeline, &ha_aircraft_config, 12345u);
  for (i = 0u; i < STEPS; ++i) {
    times_us[i] = ha_bench_timeline_next(&timeline, &in);
    inputs[i] = in;
  }
  for (run = 0u; run < RUNS; ++run) {
    double t0;
    ha_core_init(&core, &ha_aircraft_config);
    t0 = now_ns();
    for (i = 0u; i < STEPS; ++i) {
      ha_core_step(&core, &inputs[i], times_us[i], &out);
      sink += out.controller;
    }
    ns_per_step[run] = (now_ns() - t0) / (double)STEPS;
  }
  qsort(ns_per_step, RUNS, sizeof ns_per_step[0], cmp_double);
  printf("metric: host_ns_per_step_median %.1f ns\n", ns_per_step[RUNS / 2u]);
  printf("metric: host_ns_per_step_min %.1f ns\n", ns_per_step[0]);
  printf("metric: host_ns_per_step_max %.1f ns\n", ns_per_step[RUNS - 1u]);
  printf("metric: host_runs %u runs\n", RUNS);
  printf("metric: host_steps_per_run %u steps\n", STEPS);
  return sink == 0xFFFFFFFFu;
}
