/* Splits the VN-200 serial byte stream into whole packets. The sensor interleaves binary output
 * packets (sync 0xFA, length implied by their group masks) with ASCII sentences ("$VN...*XX\r\n":
 * register responses, errors, ASCII async output), so the framer keeps two paths keyed on the
 * first byte. A frame is handed out only when complete and intact (binary CRC, ASCII checksum);
 * anything else is counted by reason and skipped up to the next candidate sync byte, so a
 * corrupted or truncated packet never hides the packet behind it.
 * Bounded: one buffer of VN_FRAME_MAX bytes, no heap, no recursion. */
#ifndef VN_FRAMER_H
#define VN_FRAMER_H

#include <stddef.h>
#include <stdint.h>

#include "vn_binary.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Longest ASCII sentence accepted, "$" through "\r\n". The longest register response the VN-200
 * sends (manual, register set) is well under this. */
#define VN_ASCII_MAX 256u
#define VN_FRAME_MAX VN_BIN_MAX_PACKET

typedef enum { VN_FRAME_BINARY = 1, VN_FRAME_ASCII = 2 } VnFrameKind;

typedef struct {
  VnFrameKind kind;
  const uint8_t *data; /* valid until the next vn_framer_next() call */
  size_t len;
} VnFrame;

typedef struct {
  uint32_t binary_frames;
  uint32_t ascii_frames;
  uint32_t dropped_bytes;     /* every byte discarded: noise and the bytes of bad packets */
  uint32_t bad_binary_groups; /* groups byte zero or with an undocumented group */
  uint32_t bad_binary_field;  /* a field mask bit with no documented size */
  uint32_t bad_binary_crc;
  uint32_t bad_ascii_char; /* a non-printable byte or a lone CR/LF inside a sentence */
  uint32_t bad_ascii_too_long;
  uint32_t bad_ascii_checksum; /* missing, malformed or wrong checksum */
} VnFramerStats;

typedef struct {
  uint8_t buf[VN_FRAME_MAX];
  size_t len;
  size_t scan;    /* ASCII: bytes already examined */
  size_t need;    /* binary: packet length once the header is known, 0 before */
  size_t emitted; /* length of the frame handed out by the previous call */
  VnFramerStats stats;
} VnFramer;

void vn_framer_init(VnFramer *f);

/* Consumes bytes from data[0..len) until a frame completes or the input is used up.
 * Returns 1 with *out set when a frame completed, else 0. *consumed tells how many input bytes
 * were taken; call again with the rest (and again with len 0 until it returns 0: bytes buffered
 * after a rejected packet can hold further frames). */
int vn_framer_next(VnFramer *f, const uint8_t *data, size_t len, size_t *consumed, VnFrame *out);

uint32_t vn_framer_bad_packets(const VnFramerStats *s);

#ifdef __cplusplus
}
#endif
#endif
