#include "sil_ins.h"

#include <string.h>

#include "vn_binary.h"

/* Field for field as due_ins_sample_from_vn() (board_due/due_ins_seam.cpp), which is C++ behind
 * the Arduino API and cannot be linked into this C program. */
static void sample_from_vn(const VnBinaryData *vn, HaInsSample *s) {
  const uint32_t has = vn->has;
  size_t i;
  s->has = 0u;
  if ((has & VN_HAS_YPR) != 0u) s->has |= HA_INS_HAS_YPR;
  if ((has & VN_HAS_ANGULAR_RATE) != 0u) s->has |= HA_INS_HAS_RATE;
  if ((has & VN_HAS_POSITION_LLA) != 0u) s->has |= HA_INS_HAS_POSITION;
  if ((has & VN_HAS_VEL_NED) != 0u) s->has |= HA_INS_HAS_VEL_NED;
  if ((has & VN_HAS_INS_STATUS) != 0u) s->has |= HA_INS_HAS_STATUS;
  if ((has & VN_HAS_GPS_FIX) != 0u) s->has |= HA_INS_HAS_GPS_FIX;
  for (i = 0u; i < 3u; ++i) {
    s->ypr_deg[i] = vn->ypr_deg[i];
    s->angular_rate_radps[i] = vn->angular_rate_radps[i];
    s->vel_ned_mps[i] = vn->vel_ned_mps[i];
  }
  s->lat_deg = vn->lat_deg;
  s->lon_deg = vn->lon_deg;
  s->alt_m = vn->alt_m;
  s->ins_status = vn->ins_status;
  s->gps_fix = vn->gps_fix;
}

void sil_ins_init(SilIns *s, const HaAircraftConfig *cfg) {
  memset(s, 0, sizeof *s);
  s->cfg = cfg;
  vn_framer_init(&s->framer);
  ha_ins_init(&s->ins);
}

static void apply_packet(SilIns *s, const VnFrame *frame, HaInputs *inputs, uint32_t now_us) {
  static VnBinaryData vn;
  HaInsSample sample;
  const VnBinResult result = vn_bin_decode(frame->data, frame->len, &vn);
  if (result != VN_BIN_OK) {
    s->decode_errors++;
    if (result == VN_BIN_ERR_NONFINITE) {
      inputs->state_valid = 0u;
    }
    return;
  }
  sample_from_vn(&vn, &sample);
  (void)ha_ins_update(&s->ins, s->cfg, &sample, now_us, inputs);
}

void sil_ins_feed(SilIns *s, const uint8_t *bytes, size_t len, HaInputs *inputs, uint32_t now_us) {
  size_t offset = 0u, pass;
  s->bytes_read += len;
  for (pass = 0u; pass < len + VN_FRAME_MAX + 1u; ++pass) {
    size_t used = 0u;
    VnFrame frame;
    const int got = vn_framer_next(&s->framer, bytes + offset, len - offset, &used, &frame);
    offset += used;
    if (got == 0) {
      break;
    }
    if (frame.kind == VN_FRAME_BINARY) {
      apply_packet(s, &frame, inputs, now_us);
    }
  }
}
