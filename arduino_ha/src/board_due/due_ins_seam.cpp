#include "due_ins_seam.h"

#include <Arduino.h>

#include "due_config.h"

namespace {

DueInsDecodeFn g_decode = nullptr;
void *g_decode_ctx = nullptr;
uint32_t g_bytes_dropped = 0u;

/* At 115200 baud about 115 bytes arrive per 10 ms period; reading at most this many per loop
 * keeps one call short while the loop (far faster than the period) still keeps up. */
const size_t kMaxBytesPerPoll = 64u;

}  // namespace

void due_ins_begin(DueInsDecodeFn decode, void *ctx) {
  g_decode = decode;
  g_decode_ctx = ctx;
  Serial1.begin(DUE_VN200_BAUD);
}

void due_ins_poll(HaInputs *inputs, uint32_t now_us) {
  uint8_t bytes[kMaxBytesPerPoll];
  size_t len = 0u;
  while (len < kMaxBytesPerPoll && Serial1.available() > 0) {
    bytes[len++] = static_cast<uint8_t>(Serial1.read());
  }
  if (len == 0u) {
    return;
  }
  if (g_decode == nullptr) {
    g_bytes_dropped += static_cast<uint32_t>(len);
    return;
  }
  DueInsState state;
  if (g_decode(g_decode_ctx, bytes, len, &state) != 0) {
    due_ins_apply(&state, inputs, now_us);
  }
}

void due_ins_apply(const DueInsState *state, HaInputs *inputs, uint32_t now_us) {
  inputs->roll_deg = state->roll_deg;
  inputs->pitch_deg = state->pitch_deg;
  inputs->heading_deg = state->heading_deg;
  inputs->p_deg_s = state->p_deg_s;
  inputs->q_deg_s = state->q_deg_s;
  inputs->r_deg_s = state->r_deg_s;
  inputs->altitude_agl_ft = state->altitude_agl_ft;
  inputs->north_ft = state->north_ft;
  inputs->east_ft = state->east_ft;
  inputs->on_ground = state->on_ground;
  inputs->state_valid = 1u;
  inputs->state_rx_us = now_us;
}

uint32_t due_ins_bytes_dropped(void) { return g_bytes_dropped; }
