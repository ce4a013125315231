#include "due_ins_seam.h"

#include <Arduino.h>

#include "due_config.h"

namespace {

const HaAircraftConfig *g_cfg = nullptr;
VnFramer g_framer;
HaIns g_ins;
DueInsStats g_stats;

/* At 115200 baud about 115 bytes arrive per 10 ms period; reading at most this many per loop
 * keeps one call short while the loop (far faster than the period) still keeps up. */
const size_t kMaxBytesPerPoll = 64u;

void apply_packet(const VnFrame &frame, HaInputs *inputs, uint32_t now_us) {
  /* Static: a VnBinaryData is some 200 bytes, kept off the loop's stack. */
  static VnBinaryData vn;
  HaInsSample sample;
  const VnBinResult result = vn_bin_decode(frame.data, frame.len, &vn);
  if (result != VN_BIN_OK) {
    g_stats.decode_errors++;
    if (result == VN_BIN_ERR_NONFINITE) {
      /* The sensor sent NaN/inf: its solution cannot be trusted until a clean one arrives. */
      inputs->state_valid = 0u;
    }
    return;
  }
  due_ins_sample_from_vn(&vn, &sample);
  (void)ha_ins_update(&g_ins, g_cfg, &sample, now_us, inputs);
}

}  // namespace

void due_ins_sample_from_vn(const VnBinaryData *vn, HaInsSample *s) {
  const uint32_t has = vn->has;
  s->has = 0u;
  if ((has & VN_HAS_YPR) != 0u) s->has |= HA_INS_HAS_YPR;
  if ((has & VN_HAS_ANGULAR_RATE) != 0u) s->has |= HA_INS_HAS_RATE;
  if ((has & VN_HAS_POSITION_LLA) != 0u) s->has |= HA_INS_HAS_POSITION;
  if ((has & VN_HAS_VEL_NED) != 0u) s->has |= HA_INS_HAS_VEL_NED;
  if ((has & VN_HAS_INS_STATUS) != 0u) s->has |= HA_INS_HAS_STATUS;
  if ((has & VN_HAS_GPS_FIX) != 0u) s->has |= HA_INS_HAS_GPS_FIX;
  for (size_t i = 0u; i < 3u; ++i) {
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

void due_ins_begin(const HaAircraftConfig *cfg) {
  g_cfg = cfg;
  vn_framer_init(&g_framer);
  ha_ins_init(&g_ins);
  g_stats = DueInsStats();
  Serial1.begin(DUE_VN200_BAUD);
}

void due_ins_feed(const uint8_t *bytes, size_t len, HaInputs *inputs, uint32_t now_us) {
  if (g_cfg == nullptr) {
    return; /* not begun */
  }
  g_stats.bytes_read += static_cast<uint32_t>(len);
  size_t offset = 0u;
  /* Each pass consumes input or hands out a frame from the framer's bounded buffer, so the
   * loop ends; the cap only makes that obvious. */
  for (size_t pass = 0u; pass < len + VN_FRAME_MAX + 1u; ++pass) {
    size_t used = 0u;
    VnFrame frame;
    const int got = vn_framer_next(&g_framer, bytes + offset, len - offset, &used, &frame);
    offset += used;
    if (got == 0) {
      break;
    }
    if (frame.kind == VN_FRAME_BINARY) {
      g_stats.binary_packets++;
      apply_packet(frame, inputs, now_us);
    } else {
      g_stats.ascii_frames++;
    }
  }
}

void due_ins_poll(HaInputs *inputs, uint32_t now_us) {
  uint8_t bytes[kMaxBytesPerPoll];
  size_t len = 0u;
  while (len < kMaxBytesPerPoll && Serial1.available() > 0) {
    bytes[len++] = static_cast<uint8_t>(Serial1.read());
  }
  if (len > 0u) {
    due_ins_feed(bytes, len, inputs, now_us);
  }
}

DueInsStats due_ins_stats(void) {
  DueInsStats stats = g_stats;
  stats.bad_packets = vn_framer_bad_packets(&g_framer.stats);
  stats.solutions_used = g_ins.solutions_used;
  stats.solutions_rejected = g_ins.solutions_rejected;
  return stats;
}

const HaIns *due_ins_state(void) { return &g_ins; }

int due_ins_set_home(uint8_t use_current, double lat_deg, double lon_deg, double alt_m,
                     uint32_t now_us) {
  if (g_cfg == nullptr) return HA_INS_SET_HOME_NOT_ON_GROUND;  // before due_ins_begin
  return ha_ins_set_home(&g_ins, g_cfg, use_current, lat_deg, lon_deg, alt_m, now_us);
}
