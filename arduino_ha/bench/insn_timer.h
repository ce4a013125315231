/* Instruction counting on QEMU's mps2-an385 run with -icount shift=0: virtual time advances
 * 1 ns per executed instruction and CMSDK APB timer 0 counts that virtual time at the board's
 * 25 MHz, so one timer tick is 40 instructions. Reading the timer is an I/O access, at which
 * icount is exact. calibrate_m3.c checks this against loops of known length. */
#ifndef HA_BENCH_INSN_TIMER_H
#define HA_BENCH_INSN_TIMER_H

#include <stdint.h>

#define HA_INSN_PER_TICK 40u

void ha_insn_timer_start(void);
/* Free-running down counter in ticks; elapsed = earlier - later (mod 2^32). */
uint32_t ha_insn_timer_read(void);

#endif
