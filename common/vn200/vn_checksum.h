/* Integrity checks used by the VN-200 serial protocols.
 * VN-200 User Manual, section "Checksum / CRC" (serial interface chapter): ASCII sentences carry an
 * 8-bit XOR or a 16-bit CRC of the characters between '$' and '*'; binary packets carry the same
 * 16-bit CRC (CCITT polynomial 0x1021, initial value 0) over every byte after the sync byte. */
#ifndef VN_CHECKSUM_H
#define VN_CHECKSUM_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* CRC-16/CCITT as the sensor computes it (poly 0x1021, init 0, no reflection). Running it over a
 * binary packet's bytes after the sync, CRC included, yields 0 for an intact packet. */
uint16_t vn_crc16(const uint8_t *data, size_t len);
/* Continues a CRC over more bytes so callers can checksum pieces without copying. */
uint16_t vn_crc16_update(uint16_t crc, const uint8_t *data, size_t len);
/* 8-bit XOR of all bytes. */
uint8_t vn_xor8(const uint8_t *data, size_t len);

#ifdef __cplusplus
}
#endif
#endif
