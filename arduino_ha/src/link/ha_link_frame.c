#include "ha_link_frame.h"

#include <string.h>

static uint8_t checksum_of(uint32_t sum) { return (uint8_t)(255u - (sum % 256u)); }

void ha_link_decoder_init(HaLinkDecoder *dec, uint32_t timeout_us) {
  memset(dec, 0, sizeof *dec);
  dec->state = HA_LINK_RX_SYNC;
  dec->timeout_us = timeout_us;
}

void ha_link_decoder_poll(HaLinkDecoder *dec, uint32_t now_us) {
  /* Unsigned subtraction stays right across the 71-minute wrap of the microsecond clock. */
  if ((dec->state != HA_LINK_RX_SYNC) &&
      ((uint32_t)(now_us - dec->frame_start_us) > dec->timeout_us)) {
    dec->counters.timeouts++;
    dec->state = HA_LINK_RX_SYNC;
  }
}

bool ha_link_decoder_feed(HaLinkDecoder *dec, uint8_t byte, uint32_t now_us, HaLinkFrame *frame) {
  bool complete = false;
  ha_link_decoder_poll(dec, now_us);
  switch (dec->state) {
    case HA_LINK_RX_SYNC:
      if (byte == HA_LINK_SYNC_BYTE) {
        dec->state = HA_LINK_RX_PROTOCOL;
        dec->frame_start_us = now_us;
      } else {
        dec->counters.bytes_skipped++;
      }
      break;
    case HA_LINK_RX_PROTOCOL:
      if (byte == HA_LINK_PROTOCOL_V2) {
        dec->state = HA_LINK_RX_LEN_LO;
      } else if (byte == HA_LINK_SYNC_BYTE) {
        /* A run of 0xFF (or v1's 0xFF 0xFF): the last one may still start a frame. */
        dec->counters.bad_protocol++;
        dec->frame_start_us = now_us;
      } else {
        dec->counters.bad_protocol++;
        dec->state = HA_LINK_RX_SYNC;
      }
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
        dec->state = HA_LINK_RX_SYNC;
      } else if (dec->length > HA_LINK_MAX_PAYLOAD) {
        dec->counters.oversized++;
        dec->state = HA_LINK_RX_SYNC;
      } else {
        dec->state = HA_LINK_RX_TOPIC_LO;
      }
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
    default:
      if (((dec->sum + byte) % 256u) == 255u) {
        dec->counters.frames_ok++;
        frame->topic_id = dec->topic_id;
        frame->payload = dec->payload;
        frame->payload_len = dec->length;
        complete = true;
      } else {
        dec->counters.bad_checksum++;
      }
      dec->state = HA_LINK_RX_SYNC;
      break;
  }
  return complete;
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
