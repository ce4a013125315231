/* The HA control step on a Cortex-M3 (QEMU mps2-an385, -icount shift=0): runs the benchmark
 * timeline (bench_inputs.c) through ha_core_step and counts the instructions of every call with
 * the CMSDK timer (insn_timer.h, checked by calibrate_m3.c). Prints metric lines through
 * semihosting and exits QEMU. Also paints the stack below main's frame before the run and reports
 * how deep the steps wrote into it. */
#include <stdint.h>

#include "bench_inputs.h"
#include "ha_aircraft.h"
#include "ha_core.h"
#include "ha_ins.h"
#include "insn_timer.h"
#include "semihost.h"

#define STEPS 4000u
/* The step's budget: 2 % of the 10 ms period at the Due's 84 MHz. A hard real-time loop must meet
 * it in its worst period, so the verdict below is on the max, not the median. QEMU counts
 * instructions; the Due's flash wait states add cycles this does not see. */
#define BUDGET_INSNS 16800u
#define PAINT_BYTES 8192u
#define PAINT 0xA5A5A5A5u

static HaCore core;
static HaInputs inputs;
static HaOutputs outputs;
static HaBenchTimeline timeline;
static uint32_t insns[STEPS];
static uint32_t controller_periods[5];
static uint32_t controller_max_insns[5];

static void sort_u32(uint32_t *v, uint32_t n) {
  /* Shell sort: no recursion, no heap, fast enough for a few thousand values. */
  uint32_t gap;
  for (gap = n / 2u; gap > 0u; gap /= 2u) {
    uint32_t i;
    for (i = gap; i < n; ++i) {
      const uint32_t x = v[i];
      uint32_t j = i;
      while (j >= gap && v[j - gap] > x) {
        v[j] = v[j - gap];
        j -= gap;
      }
      v[j] = x;
    }
  }
}

static void metric(const char *name, uint32_t value, const char *unit) {
  char line[128] = "metric: ";
  ha_append_str(line, sizeof line, name);
  ha_append_str(line, sizeof line, " ");
  ha_append_u32(line, sizeof line, value);
  ha_append_str(line, sizeof line, " ");
  ha_append_str(line, sizeof line, unit);
  ha_append_str(line, sizeof line, "\n");
  ha_semihost_write0(line);
}

/* Stack words below the caller's frame; painted before the run, scanned after it. noinline
 * keeps this function's own frame out of the painted region (it starts 64 bytes below its SP). */
static __attribute__((noinline)) uintptr_t paint_stack(void) {
  uintptr_t sp;
  uint32_t i;
  __asm__ volatile("mov %0, sp" : "=r"(sp));
  sp -= 64u;
  for (i = 1u; i <= PAINT_BYTES / 4u; ++i) {
    *(volatile uint32_t *)(sp - 4u * i) = PAINT;
  }
  return sp;
}

/* Bytes below top that the run overwrote: the deepest word no longer holding the paint. */
static uint32_t stack_used_bytes(uintptr_t top) {
  uint32_t i;
  for (i = PAINT_BYTES / 4u; i > 0u; --i) {
    if (*(volatile uint32_t *)(top - 4u * i) != PAINT) {
      return i * 4u;
    }
  }
  return 0u;
}

/* The INS adapter per solution (not part of the step above: it runs as the VN-200's packets
 * arrive): home latched, then solutions up to 3000 ft from home through the geodesy module. */
static uint32_t ins_update_max_insns(void) {
  static HaIns ins;
  HaInsSample s;
  HaInputs in;
  uint32_t worst = 0u;
  uint32_t k;
  ha_ins_init(&ins);
  for (k = 0u; k < 200u; ++k) {
    uint32_t t0;
    uint32_t n;
    s.has = (uint8_t)(HA_INS_HAS_REQUIRED | HA_INS_HAS_GPS_FIX);
    s.ypr_deg[0] = 10.0f;
    s.ypr_deg[1] = 2.0f;
    s.ypr_deg[2] = -5.0f;
    s.angular_rate_radps[0] = s.angular_rate_radps[1] = s.angular_rate_radps[2] = 0.1f;
    /* A square spiral out to 0.008 deg (about 3000 ft north, 2000 ft east at 40 deg). */
    s.lat_deg = 40.4237054 + (k == 0u ? 0.0 : 0.00004 * (double)k * ((k & 1u) ? 1.0 : -1.0));
    s.lon_deg = -86.9211946 + (k == 0u ? 0.0 : 0.00004 * (double)k * ((k & 2u) ? 1.0 : -1.0));
    s.alt_m = 185.0 + (k == 0u ? 0.0 : 60.0);
    s.vel_ned_mps[0] = k == 0u ? 0.0f : 18.0f;
    s.vel_ned_mps[1] = s.vel_ned_mps[2] = 0.0f;
    s.ins_status = 0x0006u;
    s.gps_fix = 3u;
    t0 = ha_insn_timer_read();
    (void)ha_ins_update(&ins, &ha_aircraft_config, &s, 1u, 1000u * k, &in);
    n = (t0 - ha_insn_timer_read()) * HA_INSN_PER_TICK;
    worst = n > worst ? n : worst;
  }
  return worst;
}

int main(void) {
  uintptr_t painted_top;
  uint64_t sum = 0u;
  uint32_t i;
  uint32_t over_budget = 0u;

  ha_core_init(&core, &ha_aircraft_config);
  ha_bench_timeline_init(&timeline, &ha_aircraft_config, 12345u);
  ha_insn_timer_start();
  painted_top = paint_stack();
  for (i = 0u; i < STEPS; ++i) {
    const uint32_t now_us = ha_bench_timeline_next(&timeline, &inputs);
    const uint32_t t0 = ha_insn_timer_read();
    ha_core_step(&core, &inputs, now_us, &outputs);
    insns[i] = (t0 - ha_insn_timer_read()) * HA_INSN_PER_TICK;
    sum += insns[i];
    if (outputs.controller < 5u) {
      ++controller_periods[outputs.controller];
      if (insns[i] > controller_max_insns[outputs.controller]) {
        controller_max_insns[outputs.controller] = insns[i];
      }
    }
  }
  metric("m3_stack_high_water_below_main", stack_used_bytes(painted_top), "bytes");
  for (i = 0u; i < STEPS; ++i) {
    if (insns[i] >= BUDGET_INSNS) {
      ++over_budget;
    }
  }
  sort_u32(insns, STEPS);
  metric("m3_insns_per_step_median", insns[STEPS / 2u], "instructions");
  metric("m3_insns_per_step_p99", insns[(STEPS * 99u) / 100u], "instructions");
  metric("m3_insns_per_step_max", insns[STEPS - 1u], "instructions");
  metric("m3_insns_per_step_min", insns[0], "instructions");
  metric("m3_insns_per_step_budget", BUDGET_INSNS, "instructions");
  metric("m3_insns_per_step_mean", (uint32_t)(sum / STEPS), "instructions");
  metric("m3_steps_measured", STEPS, "steps");
  metric("m3_steps_over_16800_insns", over_budget, "steps");
  metric("m3_insn_count_resolution", HA_INSN_PER_TICK, "instructions");
  metric("m3_periods_hp", controller_periods[HA_CONTROLLER_HP], "periods");
  metric("m3_periods_ha", controller_periods[HA_CONTROLLER_HA], "periods");
  metric("m3_periods_recovering", controller_periods[HA_CONTROLLER_RECOVERING], "periods");
  metric("m3_periods_ha_latched", controller_periods[HA_CONTROLLER_HA_LATCHED], "periods");
  metric("m3_periods_manual", controller_periods[HA_CONTROLLER_MANUAL], "periods");
  metric("m3_insns_max_hp", controller_max_insns[HA_CONTROLLER_HP], "instructions");
  metric("m3_insns_max_ha", controller_max_insns[HA_CONTROLLER_HA], "instructions");
  metric("m3_insns_max_recovering", controller_max_insns[HA_CONTROLLER_RECOVERING], "instructions");
  metric("m3_insns_max_ha_latched", controller_max_insns[HA_CONTROLLER_HA_LATCHED], "instructions");
  metric("m3_insns_max_manual", controller_max_insns[HA_CONTROLLER_MANUAL], "instructions");
  metric("m3_insns_ins_update_max", ins_update_max_insns(), "instructions");
  {
    char line[160] = "budget: worst case ";
    const uint32_t worst = insns[STEPS - 1u];
    ha_append_u32(line, sizeof line, worst);
    ha_append_str(line, sizeof line, " of ");
    ha_append_u32(line, sizeof line, BUDGET_INSNS);
    ha_append_str(line, sizeof line, " instructions per step: ");
    ha_append_str(line, sizeof line, worst < BUDGET_INSNS ? "MET" : "NOT MET");
    ha_append_str(line, sizeof line,
                  " (2% of a 10 ms period at 84 MHz; timing is reported, never asserted)\n");
    ha_semihost_write0(line);
  }
  return 0;
}
