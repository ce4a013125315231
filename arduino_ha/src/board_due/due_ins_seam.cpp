#include "due_ins_seam.h"

#include <Arduino.h>

#include "due_config.h"

namespace {

HaVn200Feed g_feed;

/* At 115200 baud about 115 bytes arrive per 10 ms period; reading at most this many per loop
 * keeps one call short while the loop (far faster than the period) still keeps up. */
const size_t kMaxBytesPerPoll = 64u;

}  // namespace

void due_ins_begin(const HaAircraftConfig *cfg) {
  ha_vn200_feed_init(&g_feed, cfg);
  Serial1.begin(DUE_VN200_BAUD);
}

void due_ins_feed(const uint8_t *bytes, size_t len, HaInputs *inputs, uint8_t ha_on_ground,
                  uint32_t now_us) {
  ha_vn200_feed_bytes(&g_feed, bytes, len, inputs, ha_on_ground, now_us);
}

void due_ins_poll(HaInputs *inputs, uint8_t ha_on_ground, uint32_t now_us) {
  uint8_t bytes[kMaxBytesPerPoll];
  size_t len = 0u;
  while (len < kMaxBytesPerPoll && Serial1.available() > 0) {
    bytes[len++] = static_cast<uint8_t>(Serial1.read());
  }
  if (len > 0u) {
    due_ins_feed(bytes, len, inputs, ha_on_ground, now_us);
  }
}

DueInsStats due_ins_stats(void) {
  DueInsStats stats = DueInsStats();
  stats.bytes_read = static_cast<uint32_t>(g_feed.counts.bytes_read);
  stats.binary_packets = g_feed.counts.binary_packets;
  stats.ascii_frames = g_feed.counts.ascii_frames;
  stats.decode_errors = g_feed.counts.decode_errors;
  stats.bad_packets = vn_framer_bad_packets(&g_feed.framer.stats);
  stats.solutions_used = g_feed.ins.solutions_used;
  stats.solutions_rejected = g_feed.ins.solutions_rejected;
  return stats;
}

const HaIns *due_ins_state(void) { return &g_feed.ins; }

HaIns *due_ins_adapter(void) { return &g_feed.ins; }

int due_ins_set_home(uint8_t ha_on_ground, uint8_t use_current, double lat_deg, double lon_deg,
                     double alt_m) {
  if (g_feed.cfg == nullptr) return HA_INS_SET_HOME_NOT_ON_GROUND;  // before due_ins_begin
  return ha_ins_set_home(&g_feed.ins, ha_on_ground, use_current, lat_deg, lon_deg, alt_m);
}
