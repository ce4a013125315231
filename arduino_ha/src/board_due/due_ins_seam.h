/* THE VN-200 SEAM: where the decoded INS state enters the HA.
 *
 * The VN-200's port 1 is wired to the Due's Serial1. Its bytes are read here every loop and
 * handed to a decoder; a decoded state is written into the core's inputs by due_ins_apply(),
 * which is the only place INS data enters HaInputs. The decoder is the VN-200 protocol core
 * (vn200_driver/core: vn_framer + vn_bin_decode) plus a conversion to the units below; it is
 * plugged in with due_ins_begin(). Until one is plugged in, bytes are counted and dropped,
 * state_valid stays 0, and the core treats the attitude/altitude/position as unknown (its state
 * checks fail, so the HA keeps control). README.md, "VN-200", says how to wire it. */
#ifndef DUE_INS_SEAM_H
#define DUE_INS_SEAM_H

#include <stddef.h>
#include <stdint.h>

#include "../core/ha_core.h"

/* One INS solution in the core's units and frames (see HaInputs in core/ha_core.h). */
typedef struct {
  float roll_deg;    /* right wing down positive */
  float pitch_deg;   /* nose up positive */
  float heading_deg; /* true, clockwise from north */
  float p_deg_s;
  float q_deg_s;
  float r_deg_s;
  float altitude_agl_ft;
  float north_ft; /* from the home/rally point */
  float east_ft;
  uint8_t on_ground;
} DueInsState;

/* Consumes bytes from the VN-200 stream; returns 1 and fills *state when those bytes completed a
 * solution, 0 otherwise (the decoder keeps partial packets between calls). */
typedef int (*DueInsDecodeFn)(void *ctx, const uint8_t *bytes, size_t len, DueInsState *state);

/* Opens Serial1 at DUE_VN200_BAUD. decode may be NULL (not wired yet: bytes are dropped). */
void due_ins_begin(DueInsDecodeFn decode, void *ctx);

/* Reads what Serial1 has buffered (bounded per call), decodes, applies the newest state. */
void due_ins_poll(HaInputs *inputs, uint32_t now_us);

/* The seam itself: copies one decoded state into the core's inputs, stamped with its arrival.
 * No checks here: the core checks every field (finite, plausible, fresh) before use. */
void due_ins_apply(const DueInsState *state, HaInputs *inputs, uint32_t now_us);

/* Bytes read while no decoder was plugged in. */
uint32_t due_ins_bytes_dropped(void);

#endif /* DUE_INS_SEAM_H */
