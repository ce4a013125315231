#include "ha_sil_records.h"

#include <string.h>

static void put_u16(uint8_t *b, size_t *at, uint16_t v) {
  b[(*at)++] = (uint8_t)v;
  b[(*at)++] = (uint8_t)(v >> 8);
}
void ha_sil_put_u32(uint8_t *b, size_t *at, uint32_t v) {
  put_u16(b, at, (uint16_t)v);
  put_u16(b, at, (uint16_t)(v >> 16));
}
static void put_u64(uint8_t *b, size_t *at, uint64_t v) {
  ha_sil_put_u32(b, at, (uint32_t)v);
  ha_sil_put_u32(b, at, (uint32_t)(v >> 32));
}
static void put_f32(uint8_t *b, size_t *at, float v) {
  uint32_t u;
  memcpy(&u, &v, sizeof u);
  ha_sil_put_u32(b, at, u);
}
static uint16_t get_u16(const uint8_t *b, size_t *at) {
  const uint16_t v = (uint16_t)(b[*at] | (b[*at + 1u] << 8));
  *at += 2u;
  return v;
}
uint32_t ha_sil_get_u32(const uint8_t *b, size_t *at) {
  const uint32_t lo = get_u16(b, at);
  return lo | ((uint32_t)get_u16(b, at) << 16);
}
static uint64_t get_u64(const uint8_t *b, size_t *at) {
  const uint64_t lo = ha_sil_get_u32(b, at);
  return lo | ((uint64_t)ha_sil_get_u32(b, at) << 32);
}
static float get_f32(const uint8_t *b, size_t *at) {
  const uint32_t u = ha_sil_get_u32(b, at);
  float v;
  memcpy(&v, &u, sizeof v);
  return v;
}

int ha_sil_decode_step(const uint8_t *b, size_t len, HaSilStep *st) {
  size_t at = 0u;
  int k;
  if (len != HA_SIL_STEP_RECORD_LEN) {
    return 0;
  }
  st->magic = ha_sil_get_u32(b, &at);
  st->version = get_u16(b, &at);
  st->flags = get_u16(b, &at);
  st->t_us = get_u64(b, &at);
  st->vn_bytes = get_u64(b, &at);
  st->cmd_seq = ha_sil_get_u32(b, &at);
  st->wait_ms = ha_sil_get_u32(b, &at);
  for (k = 0; k < 5; ++k) {
    st->rc_pulse_us[k] = get_u16(b, &at);
  }
  st->reserved = get_u16(b, &at);
  st->airspeed_ftps = get_f32(b, &at);
  st->battery_v = get_f32(b, &at);
  return (st->magic == HA_SIL_MAGIC_STEP || st->magic == HA_SIL_MAGIC_POLL ||
          st->magic == HA_SIL_MAGIC_RESET) &&
         st->version == HA_SIL_VERSION;
}

void ha_sil_encode_reply(const HaFirmware *fw, const HaSilReplyBoard *board,
                         uint8_t out[HA_SIL_REPLY_RECORD_LEN]) {
  const HaOutputs *o = &fw->app.outputs;
  uint16_t flags = board->flags;
  size_t at = 0u;
  if (ha_link_connected(&fw->link)) flags |= HA_SIL_R_LINK_CONNECTED;
  if (fw->app.inputs.state_valid) flags |= HA_SIL_R_STATE_VALID;
  if (fw->ins.ins.home_latched) flags |= HA_SIL_R_HOME;
  if (board->hp_reset) flags |= HA_SIL_R_HP_RESET;
  if (o->restart_requested && (flags & HA_SIL_R_STEPPED)) flags |= HA_SIL_R_RESTART_REQUESTED;
  ha_sil_put_u32(out, &at, HA_SIL_MAGIC_REPLY);
  put_u16(out, &at, HA_SIL_VERSION);
  put_u16(out, &at, flags);
  put_u64(out, &at, board->t_us);
  put_f32(out, &at, o->surfaces.elevator_deg);
  put_f32(out, &at, o->surfaces.aileron_deg);
  put_f32(out, &at, o->surfaces.rudder_deg);
  put_f32(out, &at, o->surfaces.throttle);
  put_f32(out, &at, o->ha_command.elevator_deg);
  put_f32(out, &at, o->ha_command.aileron_deg);
  put_f32(out, &at, o->ha_command.rudder_deg);
  put_f32(out, &at, o->ha_command.throttle);
  out[at++] = o->controller;
  out[at++] = ha_app_leds(o);
  put_u16(out, &at, o->restart_count);
  ha_sil_put_u32(out, &at, o->reasons);
  ha_sil_put_u32(out, &at, o->reasons_at_switch);
  ha_sil_put_u32(out, &at, o->last_seq);
  ha_sil_put_u32(out, &at, board->commands);
  put_f32(out, &at, o->stable_for_s);
  put_f32(out, &at, o->state_region_max);
  put_f32(out, &at, o->actuator_region_max);
  ha_sil_put_u32(out, &at, (uint32_t)board->vn_bytes);
  ha_sil_put_u32(out, &at, fw->ins.ins.solutions_used);
  ha_sil_put_u32(out, &at, fw->ins.ins.solutions_rejected);
  ha_sil_put_u32(out, &at,
                 vn_framer_bad_packets(&fw->ins.framer.stats) + fw->ins.counts.decode_errors);
  ha_sil_put_u32(out, &at, board->wait_us);
}
