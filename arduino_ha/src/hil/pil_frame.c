#include "pil_frame.h"

#include <string.h>

#include "hp_command.h"

void pil_frame_rx_init(PilFrameRx *rx) { memset(rx, 0, sizeof *rx); }

static void drop_front(PilFrameRx *rx, size_t n) {
  memmove(rx->held, rx->held + n, rx->have - n);
  rx->have -= n;
}

size_t pil_frame_rx_byte(PilFrameRx *rx, uint8_t byte, const uint8_t **payload) {
  if (rx->frame_len > 0u) { /* the frame handed over last time is done with */
    drop_front(rx, rx->frame_len);
    rx->frame_len = 0u;
  }
  if (rx->have < sizeof rx->held) {
    rx->held[rx->have++] = byte;
  }
  /* Each pass decides on held[0] or waits for more: bounded by the bytes held. */
  while (rx->have > 0u) {
    size_t len, crc_at;
    if (rx->held[0] != PIL_FRAME_SYNC0 || (rx->have > 1u && rx->held[1] != PIL_FRAME_SYNC1)) {
      drop_front(rx, 1u);
      continue;
    }
    if (rx->have < 4u) {
      return 0u;
    }
    len = (size_t)rx->held[2] | ((size_t)rx->held[3] << 8);
    if (len == 0u || len > PIL_FRAME_RX_PAYLOAD_MAX) {
      rx->bad_length++;
      drop_front(rx, 1u);
      continue;
    }
    if (rx->have < len + PIL_FRAME_OVERHEAD) {
      return 0u;
    }
    crc_at = 4u + len;
    if (ha_crc32(&rx->held[2], len + 2u) != ha_sil_get_u32(rx->held, &crc_at)) {
      rx->bad_crc++;
      drop_front(rx, 1u);
      continue;
    }
    rx->frame_len = len + PIL_FRAME_OVERHEAD;
    *payload = &rx->held[4];
    return len;
  }
  return 0u;
}

size_t pil_frame_encode(const uint8_t *payload, size_t len, uint8_t *out, size_t out_cap) {
  size_t crc_at = 4u + len;
  if (len == 0u || len > 0xFFFFu || out_cap < len + PIL_FRAME_OVERHEAD) {
    return 0u;
  }
  out[0] = PIL_FRAME_SYNC0;
  out[1] = PIL_FRAME_SYNC1;
  out[2] = (uint8_t)len;
  out[3] = (uint8_t)(len >> 8);
  memcpy(&out[4], payload, len);
  ha_sil_put_u32(out, &crc_at, ha_crc32(&out[2], len + 2u));
  return len + PIL_FRAME_OVERHEAD;
}

void pil_reply_frame(const HaFirmware *fw, const HaSilReplyBoard *board, const PilReplyTrailer *tr,
                     uint8_t out[PIL_REPLY_FRAME_LEN]) {
  uint8_t rec[HA_SIL_REPLY_RECORD_LEN + PIL_TRAILER_LEN];
  size_t at = HA_SIL_REPLY_RECORD_LEN;
  ha_sil_encode_reply(fw, board, rec);
  ha_sil_put_u32(rec, &at, tr->records_dropped);
  ha_sil_put_u32(rec, &at, tr->period_ticks);
  ha_sil_put_u32(rec, &at, tr->tx_dropped);
  ha_sil_put_u32(rec, &at, tr->rx_dropped);
  (void)pil_frame_encode(rec, sizeof rec, out, PIL_REPLY_FRAME_LEN);
}
