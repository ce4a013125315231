/* rosserial protocol version 2 (ROS Noetic) framing on the Due, as bytes in and frames out:
 *   0xFF sync, 0xFE protocol version, length (uint16 LE), length checksum
 *   255 - ((len_lo + len_hi) % 256), topic id (uint16 LE), payload, checksum
 *   255 - ((topic_lo + topic_hi + sum(payload)) % 256).
 * The decoder takes one byte and the time at a time, keeps the bytes of at most one frame, and
 * counts every kind of bad input it drops. When a frame fails (protocol, length checksum, length,
 * checksum), the search for the next sync byte restarts one byte after the failed one, among the
 * bytes that frame had already taken: a frame that lost a byte took the next frame's sync byte
 * as its checksum, and that next frame still arrives.
 * C99, no heap, no recursion, time passed in. */
#ifndef HA_LINK_FRAME_H
#define HA_LINK_FRAME_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define HA_LINK_SYNC_BYTE 0xFFu
#define HA_LINK_PROTOCOL_V2 0xFEu
/* Bytes around the payload: sync, protocol, 2 length, length checksum, 2 topic, checksum. */
#define HA_LINK_FRAME_OVERHEAD 8u
/* The largest payload the Due accepts; also announced as buffer_size in every TopicInfo. The
 * biggest message it receives (ServoCommand, 42 bytes) fits many times; a longer announced
 * length is treated as corruption. */
#define HA_LINK_MAX_PAYLOAD 256u
/* The decoder holds every byte of the frame it parses, from its sync byte on. */
#define HA_LINK_RX_HELD_MAX (HA_LINK_MAX_PAYLOAD + HA_LINK_FRAME_OVERHEAD)

typedef struct {
  uint32_t frames_ok;           /* complete frames with both checksums right */
  uint32_t bytes_skipped;       /* not a sync byte where one was due: garbage between frames, and
                                 * the bytes of a failed frame passed over in the search for the
                                 * next sync byte */
  uint32_t bad_protocol;        /* sync followed by another protocol version (e.g. v1's 0xFF) */
  uint32_t bad_length_checksum; /* the length's own checksum does not match */
  uint32_t oversized;           /* an announced length above HA_LINK_MAX_PAYLOAD */
  uint32_t bad_checksum;        /* topic + payload checksum does not match (bit flips) */
  uint32_t timeouts;            /* a frame that stopped arriving mid-way, dropped */
} HaLinkFrameCounters;

typedef enum {
  HA_LINK_RX_SYNC = 0,
  HA_LINK_RX_PROTOCOL,
  HA_LINK_RX_LEN_LO,
  HA_LINK_RX_LEN_HI,
  HA_LINK_RX_LEN_CHECKSUM,
  HA_LINK_RX_TOPIC_LO,
  HA_LINK_RX_TOPIC_HI,
  HA_LINK_RX_PAYLOAD,
  HA_LINK_RX_CHECKSUM
} HaLinkRxState;

typedef struct {
  uint16_t topic_id;
  const uint8_t *payload; /* into the decoder: valid until its next push or next */
  uint16_t payload_len;
} HaLinkFrame;

typedef struct {
  HaLinkRxState state;
  uint16_t length;
  uint16_t received;
  uint16_t topic_id;
  uint32_t sum;
  uint32_t frame_start_us;
  uint32_t last_byte_us; /* when the latest byte was pushed */
  uint32_t timeout_us;
  /* held[start, end): the bytes taken and not yet dropped; the frame being parsed begins at
   * held[start] (its sync byte) unless state is HA_LINK_RX_SYNC, and held[start, next) have been
   * parsed. */
  uint16_t start;
  uint16_t next;
  uint16_t end;
  uint8_t held[HA_LINK_RX_HELD_MAX];
  uint8_t payload[HA_LINK_MAX_PAYLOAD]; /* of the frame being parsed; a delivered one's */
  HaLinkFrameCounters counters;
} HaLinkDecoder;

/* timeout_us: how long a started frame may take to complete before it is dropped. */
void ha_link_decoder_init(HaLinkDecoder *dec, uint32_t timeout_us);

/* Drops a partial frame older than the timeout even when no byte arrives. */
void ha_link_decoder_poll(HaLinkDecoder *dec, uint32_t now_us);

/* Takes one received byte (first dropping a partial frame older than the timeout). Call
 * ha_link_decoder_next until it returns false before pushing the next byte: one byte can complete
 * more than one frame (those a failed frame had taken). */
void ha_link_decoder_push(HaLinkDecoder *dec, uint8_t byte, uint32_t now_us);

/* Parses the bytes held; returns true with the next complete, valid frame in *frame (its payload
 * valid until the next call), false when the bytes held complete no further frame. */
bool ha_link_decoder_next(HaLinkDecoder *dec, HaLinkFrame *frame);

/* Writes a complete frame into out[0..cap). Returns its length, or 0 if payload_len is above
 * HA_LINK_MAX_PAYLOAD or the frame does not fit. */
size_t ha_link_encode_frame(uint16_t topic_id, const uint8_t *payload, size_t payload_len,
                            uint8_t *out, size_t cap);

#ifdef __cplusplus
}
#endif

#endif /* HA_LINK_FRAME_H */
