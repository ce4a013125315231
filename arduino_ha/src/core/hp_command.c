#include "hp_command.h"

#include <string.h>

uint32_t ha_crc32(const uint8_t *data, size_t len) {
  uint32_t crc = 0xFFFFFFFFu;
  size_t i;
  for (i = 0u; i < len; ++i) {
    int bit;
    crc ^= (uint32_t)data[i];
    /* Bitwise rather than a 1 KiB table: 38 bytes a period do not justify the Due's RAM. */
    for (bit = 0; bit < 8; ++bit) {
      const uint32_t mask = (uint32_t)0u - (crc & 1u);
      crc = (crc >> 1) ^ (0xEDB88320u & mask);
    }
  }
  return crc ^ 0xFFFFFFFFu;
}

static void put_u32_le(uint8_t *out, uint32_t v) {
  out[0] = (uint8_t)(v & 0xFFu);
  out[1] = (uint8_t)((v >> 8) & 0xFFu);
  out[2] = (uint8_t)((v >> 16) & 0xFFu);
  out[3] = (uint8_t)((v >> 24) & 0xFFu);
}

static void put_f32_le(uint8_t *out, float f) {
  uint32_t bits;
  /* memcpy is the defined way to read a float's IEEE-754 bits in C99. */
  memcpy(&bits, &f, sizeof bits);
  put_u32_le(out, bits);
}

void ha_hp_command_pack_fields(const HaHpCommand *cmd, uint8_t out[HA_HP_COMMAND_FIELDS_LEN]) {
  put_u32_le(&out[0], cmd->seq);
  put_u32_le(&out[4], cmd->stamp_sec);
  put_u32_le(&out[8], cmd->stamp_nsec);
  put_f32_le(&out[12], cmd->throttle);
  put_f32_le(&out[16], cmd->elevator_deg);
  put_f32_le(&out[20], cmd->aileron_deg);
  put_f32_le(&out[24], cmd->rudder_deg);
  put_f32_le(&out[28], cmd->alpha_est_deg);
  put_f32_le(&out[32], cmd->beta_est_deg);
  out[36] = cmd->estimator_converged;
  out[37] = cmd->sensor_links_healthy;
}

uint32_t ha_hp_command_compute_crc(const HaHpCommand *cmd) {
  uint8_t fields[HA_HP_COMMAND_FIELDS_LEN];
  ha_hp_command_pack_fields(cmd, fields);
  return ha_crc32(fields, sizeof fields);
}
