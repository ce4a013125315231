#include "ha_retained.h"

#include <string.h>

#include "hp_command.h"

/* words[4]: magic in the top 16 bits, the layout's version, then the flags; words[5] and
 * words[6] are spare (zero); words[7] the CRC. */
#define HA_RETAINED_MAGIC 0x4852u /* "HR" */
#define HA_RETAINED_VERSION 1u
#define HA_RETAINED_AIRBORNE 0x01u
#define HA_RETAINED_RESTART_LATCHED 0x02u
#define HA_RETAINED_GROUND_COMMAND 0x04u
#define HA_RETAINED_HOME 0x08u
#define HA_RETAINED_HEADER ((HA_RETAINED_MAGIC << 16) | (HA_RETAINED_VERSION << 8))
#define HA_RETAINED_E7 1.0e7
#define HA_RETAINED_MM_PER_M 1000.0

/* Rounded to the nearest integer of v * scale, v first bounded to [-limit, limit] (home is in
 * range when latched; the bound keeps the conversion defined whatever it is handed). */
static uint32_t to_fixed(double v, double limit, double scale) {
  const double bounded = (v != v) ? 0.0 : (v < -limit ? -limit : (v > limit ? limit : v));
  const double scaled = bounded * scale;
  return (uint32_t)(int32_t)(scaled + (scaled >= 0.0 ? 0.5 : -0.5));
}

static double from_fixed(uint32_t w, double scale) { return (double)(int32_t)w / scale; }

/* CRC-32 of the first seven words, little endian whatever the machine. */
static uint32_t record_crc(const uint32_t words[HA_RETAINED_WORDS]) {
  uint8_t b[4u * (HA_RETAINED_WORDS - 1u)] = {0u};
  uint32_t i;
  for (i = 0u; i < 4u * (HA_RETAINED_WORDS - 1u); ++i) {
    b[i] = (uint8_t)(words[i / 4u] >> (8u * (i % 4u)));
  }
  return ha_crc32(b, sizeof b);
}

void ha_retained_pack(const HaRetained *r, uint32_t words[HA_RETAINED_WORDS]) {
  uint32_t flags = 0u;
  memset(words, 0, HA_RETAINED_WORDS * sizeof words[0]);
  if (r->home_latched) {
    words[0] = to_fixed(r->home_lat_deg, 90.0, HA_RETAINED_E7);
    words[1] = to_fixed(r->home_lon_deg, 180.0, HA_RETAINED_E7);
    words[2] = to_fixed(r->home_alt_m, 2.0e6, HA_RETAINED_MM_PER_M);
    words[3] = r->home_seq;
    flags |= HA_RETAINED_HOME;
  }
  flags |= r->airborne ? HA_RETAINED_AIRBORNE : 0u;
  flags |= r->restart_latched ? HA_RETAINED_RESTART_LATCHED : 0u;
  flags |= r->ground_command ? HA_RETAINED_GROUND_COMMAND : 0u;
  words[4] = HA_RETAINED_HEADER | flags;
  words[7] = record_crc(words);
}

int ha_retained_unpack(const uint32_t words[HA_RETAINED_WORDS], HaRetained *r) {
  const uint32_t flags = words[4] & 0xFFu;
  memset(r, 0, sizeof *r);
  if ((words[4] & 0xFFFFFF00u) != HA_RETAINED_HEADER || words[7] != record_crc(words)) {
    return 0;
  }
  r->airborne = (uint8_t)((flags & HA_RETAINED_AIRBORNE) != 0u);
  r->restart_latched = (uint8_t)((flags & HA_RETAINED_RESTART_LATCHED) != 0u);
  r->ground_command = (uint8_t)((flags & HA_RETAINED_GROUND_COMMAND) != 0u);
  r->home_latched = (uint8_t)((flags & HA_RETAINED_HOME) != 0u);
  if (r->home_latched) {
    r->home_lat_deg = from_fixed(words[0], HA_RETAINED_E7);
    r->home_lon_deg = from_fixed(words[1], HA_RETAINED_E7);
    r->home_alt_m = from_fixed(words[2], HA_RETAINED_MM_PER_M);
    r->home_seq = words[3];
  }
  return 1;
}
