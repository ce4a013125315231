#include "ha_vn200_feed.h"

#include <string.h>

void ha_vn200_sample_from_vn(const VnBinaryData *vn, HaInsSample *s) {
  const uint32_t has = vn->has;
  size_t i;
  s->has = 0u;
  if ((has & VN_HAS_YPR) != 0u) s->has |= HA_INS_HAS_YPR;
  if ((has & VN_HAS_ANGULAR_RATE) != 0u) s->has |= HA_INS_HAS_RATE;
  if ((has & VN_HAS_POSITION_LLA) != 0u) s->has |= HA_INS_HAS_POSITION;
  if ((has & VN_HAS_VEL_NED) != 0u) s->has |= HA_INS_HAS_VEL_NED;
  if ((has & VN_HAS_INS_STATUS) != 0u) s->has |= HA_INS_HAS_STATUS;
  if ((has & VN_HAS_GPS_FIX) != 0u) s->has |= HA_INS_HAS_GPS_FIX;
  if ((has & VN_HAS_ACCEL) != 0u) s->has |= HA_INS_HAS_ACCEL;
  for (i = 0u; i < 3u; ++i) {
    s->ypr_deg[i] = vn->ypr_deg[i];
    s->angular_rate_radps[i] = vn->angular_rate_radps[i];
    s->vel_ned_mps[i] = vn->vel_ned_mps[i];
    s->accel_mps2[i] = vn->accel_mps2[i];
  }
  s->lat_deg = vn->lat_deg;
  s->lon_deg = vn->lon_deg;
  s->alt_m = vn->alt_m;
  s->ins_status = vn->ins_status;
  s->gps_fix = vn->gps_fix;
}

void ha_vn200_feed_init(HaVn200Feed *feed, const HaAircraftConfig *cfg) {
  memset(feed, 0, sizeof *feed);
  feed->cfg = cfg;
  vn_framer_init(&feed->framer);
  ha_ins_init(&feed->ins);
}

static void apply_packet(HaVn200Feed *feed, const VnFrame *frame, HaInputs *inputs,
                         uint8_t ha_on_ground, uint32_t now_us) {
  HaInsSample sample;
  const VnBinResult result = vn_bin_decode(frame->data, frame->len, &feed->scratch);
  if (result != VN_BIN_OK) {
    /* NaN/inf in a CRC-valid packet is dropped like any rejected solution: the last good state
     * stays and the core's state_timeout_s ages it out. Invalidating it here made one such
     * packet a takeover and kept the HP out for the whole stable window. */
    feed->counts.decode_errors++;
    return;
  }
  ha_vn200_sample_from_vn(&feed->scratch, &sample);
  (void)ha_ins_update(&feed->ins, feed->cfg, &sample, ha_on_ground, now_us, inputs);
}

/* The framer hands out one frame per call, so a byte may complete one and the next call take
 * none; each byte goes in by itself (the framer's output does not depend on how the stream is
 * cut), which keeps every read it makes inside that one byte for any reader, EVA included. */
static void feed_byte(HaVn200Feed *feed, const uint8_t *byte, HaInputs *inputs,
                      uint8_t ha_on_ground, uint32_t now_us) {
  size_t left = 1u;
  size_t pass;
  /* Each pass takes the byte or hands out a frame from the framer's bounded buffer, so the loop
   * ends; the cap only makes that obvious. */
  for (pass = 0u; pass < VN_FRAME_MAX + 2u; ++pass) {
    size_t used = 0u;
    VnFrame frame;
    int got;
    memset(&frame, 0, sizeof frame); /* defined on every path: EVA needs no path reasoning */
    got = vn_framer_next(&feed->framer, byte, left, &used, &frame);
    left = used < left ? left - used : 0u;
    if (got == 0) {
      return;
    }
    if (frame.kind == VN_FRAME_BINARY) {
      feed->counts.binary_packets++;
      apply_packet(feed, &frame, inputs, ha_on_ground, now_us);
    } else {
      feed->counts.ascii_frames++;
    }
  }
}

void ha_vn200_feed_bytes(HaVn200Feed *feed, const uint8_t *bytes, size_t len, HaInputs *inputs,
                         uint8_t ha_on_ground, uint32_t now_us) {
  size_t k;
  if (feed->cfg == NULL) {
    return; /* not initialised */
  }
  feed->counts.bytes_read += len;
  for (k = 0u; k < len; ++k) {
    feed_byte(feed, &bytes[k], inputs, ha_on_ground, now_us);
  }
}
