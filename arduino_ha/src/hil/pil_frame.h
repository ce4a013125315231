/* The control records on a byte stream (the QEMU board's third UART, ../../pil/; the real Due's
 * native USB port in its HIL build, ../board_due/due_hil_board.h), unlike the SIL's unix socket
 * (one record a packet), so each record travels framed and checked:
 *
 *   0xA5 0x5A | length (u16 LE) | payload (length bytes) | CRC-32 (u32 LE) of length and payload
 *
 * (the CRC is core/hp_command.h's ha_crc32, zlib's). The payload is a record of
 * ha_sil_channel.h; the board's replies carry the reply record and its PilReplyTrailer.
 * A frame whose length is out of range or whose CRC fails is counted and dropped, never applied;
 * the receiver then looks for the next sync from the byte after the bad frame's first, so a good
 * frame that followed a damaged one inside the held bytes is still found. C99, no heap. */
#ifndef PIL_FRAME_H
#define PIL_FRAME_H

#include <stddef.h>
#include <stdint.h>

#include "ha_sil_records.h"

#ifdef __cplusplus
extern "C" {
#endif

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

/* What a board adds behind the reply record: its own counts, for the simulator's log. */
typedef struct {
  uint32_t records_dropped; /* frames out of length, failing their CRC, or holding no step, poll
                               or reset record */
  uint32_t period_ticks;    /* the period's own time, in the board's unit (README.md) */
  uint32_t tx_dropped;      /* bytes a port's host side did not take */
  uint32_t rx_dropped;      /* bytes that came to a full receive ring */
} PilReplyTrailer;
#define PIL_TRAILER_LEN 16u
#define PIL_REPLY_FRAME_LEN (HA_SIL_REPLY_RECORD_LEN + PIL_TRAILER_LEN + PIL_FRAME_OVERHEAD)

/* The reply frame of the firmware's latest period: the reply record, the trailer, framed. */
void pil_reply_frame(const HaFirmware *fw, const HaSilReplyBoard *board, const PilReplyTrailer *tr,
                     uint8_t out[PIL_REPLY_FRAME_LEN]);

#ifdef __cplusplus
}
#endif

#endif /* PIL_FRAME_H */
