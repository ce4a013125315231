/* ARM semihosting (bkpt 0xab on M-profile): QEMU's -semihosting turns these into host stdout
 * writes and a clean exit of the emulator. */
#ifndef HA_BENCH_SEMIHOST_H
#define HA_BENCH_SEMIHOST_H

#include <stdint.h>

void ha_semihost_write0(const char *text);
/* success != 0 exits QEMU with status 0, otherwise with status 1. Never returns. */
void ha_semihost_exit(int success) __attribute__((noreturn));
/* Appends the decimal value of v to a NUL-terminated line buffer of size cap. */
void ha_append_u32(char *line, uint32_t cap, uint32_t v);
void ha_append_str(char *line, uint32_t cap, const char *s);

#endif
