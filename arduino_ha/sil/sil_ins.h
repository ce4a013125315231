/* The SIL's VN-200 port: the host counterpart of src/board_due/due_ins_seam.cpp (which reads the
 * Due's Serial1 through the Arduino API). The same C99 vn200 core splits and decodes the stream
 * (vn_framer_next, vn_bin_decode, vn200_driver/core, what the Due's sketch is assembled with) and the same INS
 * adapter (core/ha_ins.c) writes the state into HaInputs; only the byte source differs. */
#ifndef SIL_INS_H
#define SIL_INS_H

#include <stddef.h>
#include <stdint.h>

#include "../src/core/ha_config.h"
#include "../src/core/ha_core.h"
#include "../src/core/ha_ins.h"
#include "vn_framer.h"

typedef struct {
  const HaAircraftConfig *cfg;
  VnFramer framer;
  HaIns ins;
  uint64_t bytes_read;
  uint32_t decode_errors;
} SilIns;

void sil_ins_init(SilIns *s, const HaAircraftConfig *cfg);

/* Frames, decodes and applies bytes received at now_us (partial packets kept for the next call). */
void sil_ins_feed(SilIns *s, const uint8_t *bytes, size_t len, HaInputs *inputs, uint32_t now_us);

#endif /* SIL_INS_H */
