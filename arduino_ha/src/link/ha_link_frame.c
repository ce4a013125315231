#include "ha_link_frame.h"

#include <string.h>

static uint8_t checksum_of(uint32_t sum) { return (uint8_t)(255u - (sum % 256u)); }

/* What one byte did to the frame being parsed. */
typedef enum { STEP_MORE = 0, STEP_FAILED, STEP_FRAME } HaLinkStep;

void ha_link_decoder_init(HaLinkDecoder *dec, uint32_t timeout_us) {
  memset(dec, 0, sizeof *dec);
  dec->state = HA_LINK_RX_SYNC;
  dec->timeout_us = timeout_us;
}

void ha_link_decoder_poll(HaLinkDecoder *dec, uint32_t now_us) {
  /* Unsigned subtraction stays right across the 71-minute wrap of the microsecond clock. A frame
   * that stopped arriving is stale, and so is anything inside it: all it holds is dropped. */
  if ((dec->state != HA_LINK_RX_SYNC) &&
      ((uint32_t)(now_us - dec->frame_start_us) > dec->timeout_us)) {
    dec->counters.timeouts++;
    dec->state = HA_LINK_RX_SYNC;
    dec->start = 0u;
    dec->next = 0u;
    dec->end = 0u;
  }
}

void ha_link_decoder_push(HaLinkDecoder *dec, uint8_t byte, uint32_t now_us) {
  ha_link_decoder_poll(dec, now_us);
  dec->last_byte_us = now_us;
  if (dec->start >= dec->end) { /* nothing held: start over at the front, no copy */
    dec->start = 0u;
    dec->next = 0u;
    dec->end = 0u;
  }
  if ((dec->end >= HA_LINK_RX_HELD_MAX) && (dec->start > 0u) && (dec->start <= dec->end) &&
      (dec->next >= dec->start) && (dec->next <= dec->end)) {
    /* Full: what lies before the frame being parsed has been dropped; move the frame forward
     * (an indexed copy, each index checked: the bounds stay local for EVA and readers). */
    size_t to = 0u;
    size_t from = dec->start;
    while ((from < dec->end) && (from < HA_LINK_RX_HELD_MAX) && (to < HA_LINK_RX_HELD_MAX)) {
      dec->held[to] = dec->held[from];
      ++to;
      ++from;
    }
    dec->next = (uint16_t)(dec->next - dec->start);
    dec->end = (uint16_t)to;
    dec->start = 0u;
  }
  if (dec->end < HA_LINK_RX_HELD_MAX) {
    dec->held[dec->end] = byte;
    dec->end++;
  } else {
    /* Only a caller that pushes without draining ha_link_decoder_next gets here: a frame and its
     * checksum never take more than HA_LINK_RX_HELD_MAX bytes. */
    dec->counters.bytes_skipped++;
  }
}

/* One byte of the frame after its sync byte. Counts a failure; the caller searches again. */
static HaLinkStep step(HaLinkDecoder *dec, uint8_t byte) {
  switch (dec->state) {
    case HA_LINK_RX_PROTOCOL:
      if (byte != HA_LINK_PROTOCOL_V2) {
        dec->counters.bad_protocol++; /* v1, or a run of 0xFF: the next may still start one */
        return STEP_FAILED;
      }
      dec->state = HA_LINK_RX_LEN_LO;
      break;
    case HA_LINK_RX_LEN_LO:
      dec->length = byte;
      dec->state = HA_LINK_RX_LEN_HI;
      break;
    case HA_LINK_RX_LEN_HI:
      dec->length = (uint16_t)(dec->length | ((uint16_t)byte << 8));
      dec->state = HA_LINK_RX_LEN_CHECKSUM;
      break;
    case HA_LINK_RX_LEN_CHECKSUM: {
      const uint32_t len_sum =
          (uint32_t)(dec->length & 0xFFu) + (uint32_t)(dec->length >> 8) + byte;
      if ((len_sum % 256u) != 255u) {
        dec->counters.bad_length_checksum++;
        return STEP_FAILED;
      }
      if (dec->length > HA_LINK_MAX_PAYLOAD) {
        dec->counters.oversized++;
        return STEP_FAILED;
      }
      dec->state = HA_LINK_RX_TOPIC_LO;
      break;
    }
    case HA_LINK_RX_TOPIC_LO:
      dec->topic_id = byte;
      dec->sum = byte;
      dec->state = HA_LINK_RX_TOPIC_HI;
      break;
    case HA_LINK_RX_TOPIC_HI:
      dec->topic_id = (uint16_t)(dec->topic_id | ((uint16_t)byte << 8));
      dec->sum += byte;
      dec->received = 0u;
      dec->state = (dec->length == 0u) ? HA_LINK_RX_CHECKSUM : HA_LINK_RX_PAYLOAD;
      break;
    case HA_LINK_RX_PAYLOAD:
      /* length <= HA_LINK_MAX_PAYLOAD was checked above, so received stays in bounds. */
      if (dec->received < HA_LINK_MAX_PAYLOAD) {
        dec->payload[dec->received] = byte;
      }
      dec->received++;
      dec->sum += byte;
      if (dec->received >= dec->length) {
        dec->state = HA_LINK_RX_CHECKSUM;
      }
      break;
    case HA_LINK_RX_CHECKSUM:
    case HA_LINK_RX_SYNC:
    default:
      if (((dec->sum + byte) % 256u) != 255u) {
        dec->counters.bad_checksum++;
        return STEP_FAILED;
      }
      dec->counters.frames_ok++;
      return STEP_FRAME;
  }
  return STEP_MORE;
}

bool ha_link_decoder_next(HaLinkDecoder *dec, HaLinkFrame *frame) {
  while ((dec->next < dec->end) && (dec->next < HA_LINK_RX_HELD_MAX)) {
    const uint8_t byte = dec->held[dec->next];
    dec->next++;
    if (dec->state == HA_LINK_RX_SYNC) {
      if (byte == HA_LINK_SYNC_BYTE) {
        dec->state = HA_LINK_RX_PROTOCOL;
        dec->frame_start_us = dec->last_byte_us; /* held bytes: as late as the latest one */
      } else {
        dec->counters.bytes_skipped++;
        dec->start = dec->next;
      }
    } else {
      const HaLinkStep result = step(dec, byte);
      if (result == STEP_FRAME) {
        frame->topic_id = dec->topic_id;
        frame->payload = dec->payload;
        frame->payload_len = dec->length;
        dec->state = HA_LINK_RX_SYNC;
        dec->start = dec->next;
        return true;
      }
      if (result == STEP_FAILED) {
        /* Search again from the byte after the failed frame's sync byte. */
        dec->state = HA_LINK_RX_SYNC;
        dec->start++;
        dec->next = dec->start;
      }
    }
  }
  return false;
}

size_t ha_link_encode_frame(uint16_t topic_id, const uint8_t *payload, size_t payload_len,
                            uint8_t *out, size_t cap) {
  size_t i;
  uint32_t sum;
  if ((payload_len > HA_LINK_MAX_PAYLOAD) || (cap < HA_LINK_FRAME_OVERHEAD) ||
      (payload_len > cap - HA_LINK_FRAME_OVERHEAD) || ((payload_len > 0u) && (payload == NULL))) {
    return 0u;
  }
  out[0] = HA_LINK_SYNC_BYTE;
  out[1] = HA_LINK_PROTOCOL_V2;
  out[2] = (uint8_t)(payload_len & 0xFFu);
  out[3] = (uint8_t)((payload_len >> 8) & 0xFFu);
  out[4] = checksum_of((uint32_t)out[2] + out[3]);
  out[5] = (uint8_t)(topic_id & 0xFFu);
  out[6] = (uint8_t)((topic_id >> 8) & 0xFFu);
  sum = (uint32_t)out[5] + out[6];
  for (i = 0u; i < payload_len; ++i) {
    out[7u + i] = payload[i];
    sum += payload[i];
  }
  out[7u + payload_len] = checksum_of(sum);
  return payload_len + HA_LINK_FRAME_OVERHEAD;
}
