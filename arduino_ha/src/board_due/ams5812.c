#include "ams5812.h"

#include <math.h>

/* Counts below this are not a reading: the output stage never goes under its 10 % point by more
 * than noise, but a missing sensor or a shorted bus reads 0. */
#define AMS5812_COUNTS_PLAUSIBLE_MIN 1000u

static float counts_to_linear(uint32_t counts, float at_min, float at_max) {
  const float fraction =
      ((float)counts - AMS5812_COUNTS_AT_MIN) / (AMS5812_COUNTS_AT_MAX - AMS5812_COUNTS_AT_MIN);
  return at_min + fraction * (at_max - at_min);
}

int ams5812_decode(const uint8_t bytes[AMS5812_READ_LEN], float p_min_pa, float p_max_pa,
                   Ams5812Reading *out) {
  uint32_t p_counts;
  uint32_t t_counts;
  if ((bytes[0] & 0x80u) != 0u || (bytes[2] & 0x80u) != 0u) {
    return 0;
  }
  p_counts = ((uint32_t)bytes[0] << 8) | (uint32_t)bytes[1];
  t_counts = ((uint32_t)bytes[2] << 8) | (uint32_t)bytes[3];
  if (p_counts < AMS5812_COUNTS_PLAUSIBLE_MIN || t_counts < AMS5812_COUNTS_PLAUSIBLE_MIN) {
    return 0;
  }
  out->diff_pressure_pa = counts_to_linear(p_counts, p_min_pa, p_max_pa);
  out->temperature_c = counts_to_linear(t_counts, AMS5812_TEMP_MIN_C, AMS5812_TEMP_MAX_C);
  return 1;
}

float ams5812_airspeed_ftps(float diff_pressure_pa) {
  if (!(diff_pressure_pa > 0.0f)) {
    return 0.0f;
  }
  return sqrtf(2.0f * diff_pressure_pa / AMS5812_RHO_SEA_LEVEL_KG_M3) * AMS5812_FT_PER_M;
}
