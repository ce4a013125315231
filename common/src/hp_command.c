#include "hp_command.h"

#include <string.h>

/* CRC-32 of the reflected polynomial for each 4-bit value: 64 bytes of flash, a table lookup per
 * nibble instead of eight shift-and-xor rounds per byte. */
static const uint32_t kCrcNibble[16] = {0x00000000u, 0x1DB71064u, 0x3B6E20C8u, 0x26D930ACu,
                                        0x76DC4190u, 0x6B6B51F4u, 0x4DB26158u, 0x5005713Cu,
                                        0xEDB88320u, 0xF00F9344u, 0xD6D6A3E8u, 0xCB61B38Cu,
                                        0x9B64C2B0u, 0x86D3D2D4u, 0xA00AE278u, 0xBDBDF21Cu};

uint32_t ha_crc32(const uint8_t *data, size_t len) {
  uint32_t crc = 0xFFFFFFFFu;
  size_t i;
  for (i = 0u; i < len; ++i) {
    crc ^= (uint32_t)data[i];
    crc = (crc >> 4) ^ kCrcNibble[crc & 0x0Fu];
    crc = (crc >> 4) ^ kCrcNibble[crc & 0x0Fu];
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
