#include "insn_timer.h"

/* CMSDK APB timer 0 on mps2-an385 (AN385 application note, memory map). */
#define TIMER0_BASE 0x40000000u
#define TIMER_CTRL (*(volatile uint32_t *)(TIMER0_BASE + 0x00u))
#define TIMER_VALUE (*(volatile uint32_t *)(TIMER0_BASE + 0x04u))
#define TIMER_RELOAD (*(volatile uint32_t *)(TIMER0_BASE + 0x08u))
#define TIMER_CTRL_ENABLE 0x1u

void ha_insn_timer_start(void) {
  TIMER_CTRL = 0u;
  TIMER_RELOAD = 0xFFFFFFFFu;
  TIMER_VALUE = 0xFFFFFFFFu;
  TIMER_CTRL = TIMER_CTRL_ENABLE;
}

uint32_t ha_insn_timer_read(void) { return TIMER_VALUE; }
