/* The control records on the QEMU board's third UART: a byte stream, unlike the SIL's unix socket
 * (one record a packet), so each record travels framed and checked:
 *
 *   0xA5 0x5A | length (u16 LE) | payload (length bytes) | CRC-32 (u32 LE) of length and payload
 *
 * (the CRC is core/hp_command.h's ha_crc32, zlib's). The payload is a record of
 * ../sil/ha_sil_channel.h; the board's replies carry the reply record and its PilReplyTrailer.
 * A frame whose length is out of range or whose CRC fails is counted and dropped, never applied;
 * the receiver then looks for the next sync from the byte after the bad frame's first, so a good
 * frame that followed a damaged one inside the held bytes is still found. C99, no heap. */
#ifndef PIL_FRAME_H
#define PIL_FRAME_H

#include <stddef.h>
#include <stdint.h>

#define PIL_FRAME_SYNC0 0xA5u
#define PIL_FRAME_SYNC1 0x5Au
#define PIL_FRAME_OVERHEAD 8u
/* The largest payload the board takes: a step record is 52 bytes. */
#define PIL_FRAME_RX_PAYLOAD_MAX 64u
#define PIL_FRAME_RX_MAX (PIL_FRAME_RX_PAYLOAD_MAX + PIL_FRAME_OVERHEAD)

typedef struct {
  uint8_t held[PIL_FRAME_RX_MAX];
  size_t have;
  size_t frame_len; /* > 0: held[] starts with a whole good frame of this many bytes, taken */
  uint32_t bad_length;
  uint32_t bad_crc;
} PilFrameRx;

void pil_frame_rx_init(PilFrameRx *rx);
/* One byte of the stream. Returns the payload's length when this byte completes a good frame
 * (the payload then at *payload until the next call), else 0. */
size_t pil_frame_rx_byte(PilFrameRx *rx, uint8_t byte, const uint8_t **payload);
/* Frames payload into out (capacity out_cap); returns the frame's length, 0 if it does not fit. */
size_t pil_frame_encode(const uint8_t *payload, size_t len, uint8_t *out, size_t out_cap);

#endif /* PIL_FRAME_H */
