/* Bare-metal start for a Cortex-M3 image: vector table, .data copy, .bss clear, main, then a
 * semihosting exit so QEMU stops by itself. Shared by the benchmark (mps2-an385) and the Due size
 * image; neither needs anything from a vendor SDK. */
#include <stdint.h>

#include "semihost.h"

extern uint32_t _data_load;
extern uint32_t _data_start;
extern uint32_t _data_end;
extern uint32_t _bss_start;
extern uint32_t _bss_end;
extern uint32_t _stack_top;

int main(void);
void ha_bench_reset_handler(void);
void ha_bench_fault_handler(void);

void ha_bench_reset_handler(void) {
  uint32_t *src = &_data_load;
  uint32_t *dst = &_data_start;
  while (dst < &_data_end) {
    *dst++ = *src++;
  }
  for (dst = &_bss_start; dst < &_bss_end; ++dst) {
    *dst = 0u;
  }
  ha_semihost_exit(main() == 0);
}

/* Any fault ends the run with a failure status instead of hanging until the timeout. */
void ha_bench_fault_handler(void) {
  ha_semihost_write0("fault: cpu exception\n");
  ha_semihost_exit(0);
}

typedef void (*HaVector)(void);

/* Initial stack pointer, reset, then NMI, HardFault, MemManage, BusFault, UsageFault. */
__attribute__((section(".isr_vector"), used)) static const HaVector ha_vectors[7] = {
    (HaVector)(uintptr_t)&_stack_top, ha_bench_reset_handler, ha_bench_fault_handler,
    ha_bench_fault_handler,           ha_bench_fault_handler, ha_bench_fault_handler,
    ha_bench_fault_handler,
};
