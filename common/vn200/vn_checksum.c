#include "vn_checksum.h"

uint16_t vn_crc16_update(uint16_t crc, const uint8_t *data, size_t len) {
  size_t i;
  if (data == NULL) {
    return crc;
  }
  for (i = 0u; i < len; ++i) {
    /* Byte-wise form of the MSB-first 0x1021 CRC; avoids a 512-byte table on the Due. */
    uint16_t c = (uint16_t)((uint16_t)(crc >> 8) | (uint16_t)(crc << 8));
    c ^= (uint16_t)data[i];
    c ^= (uint16_t)((c & 0xFFu) >> 4);
    c ^= (uint16_t)(c << 12);
    c ^= (uint16_t)((c & 0xFFu) << 5);
    crc = c;
  }
  return crc;
}

uint16_t vn_crc16(const uint8_t *data, size_t len) { return vn_crc16_update(0u, data, len); }

uint8_t vn_xor8(const uint8_t *data, size_t len) {
  uint8_t x = 0u;
  size_t i;
  if (data == NULL) {
    return 0u;
  }
  for (i = 0u; i < len; ++i) {
    x ^= data[i];
  }
  return x;
}
