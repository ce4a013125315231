#include "semihost.h"

#define SYS_WRITE0 0x04
#define SYS_EXIT 0x18
/* ADP_Stopped_ApplicationExit: QEMU exits 0; any other reason exits 1. */
#define ADP_STOPPED_APPLICATION_EXIT 0x20026
#define ADP_STOPPED_RUNTIME_ERROR 0x20023

static uint32_t semihost_call(uint32_t op, uint32_t arg) {
  register uint32_t r0 __asm__("r0") = op;
  register uint32_t r1 __asm__("r1") = arg;
  __asm__ volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory");
  return r0;
}

void ha_semihost_write0(const char *text) {
  (void)semihost_call(SYS_WRITE0, (uint32_t)(uintptr_t)text);
}

void ha_semihost_exit(int success) {
  (void)semihost_call(SYS_EXIT, success ? ADP_STOPPED_APPLICATION_EXIT : ADP_STOPPED_RUNTIME_ERROR);
  for (;;) {
  }
}

void ha_append_str(char *line, uint32_t cap, const char *s) {
  uint32_t n = 0u;
  while (n < cap && line[n] != '\0') {
    ++n;
  }
  while (n + 1u < cap && *s != '\0') {
    line[n++] = *s++;
  }
  if (n < cap) {
    line[n] = '\0';
  }
}

void ha_append_u32(char *line, uint32_t cap, uint32_t v) {
  char digits[11];
  int i = 10;
  digits[10] = '\0';
  do {
    digits[--i] = (char)('0' + (v % 10u));
    v /= 10u;
  } while (v != 0u && i > 0);
  ha_append_str(line, cap, &digits[i]);
}
