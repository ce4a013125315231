#include "ha_region.h"

#include <string.h>

#include "ha_num.h"

/* Actuator values are clamped to +/- this before the product: any real region is far smaller, so
 * the verdict is unchanged, and the sums can neither overflow nor meet inf - inf. */
#define HA_REGION_SPAN 1.0e6f

/* Exactly +/-0 (integer test on its bits: no soft-float call on the Cortex-M3). A zero
 * coefficient adds +/-0 to the row and a zero centre subtracts nothing, so skipping either
 * changes no result. */
static int is_exact_zero(float c) {
  uint32_t bits;
  memcpy(&bits, &c, sizeof bits);
  return (bits & 0x7FFFFFFFu) == 0u;
}

/* One row of S d. Only nonzero coefficients are multiplied (S_x is sparse: one nonzero per row
 * for a box region), and the first term is taken as it is rather than added to 0: on the Due
 * every float operation is a library call, and 0 + t differs from t only in the sign of a zero. */
static float row_value(const float *row, const float *d, uint32_t dim) {
  float sum = 0.0f;
  int started = 0;
  uint32_t j;
  for (j = 0u; j < dim; ++j) {
    if (!is_exact_zero(row[j])) {
      const float term = row[j] * d[j];
      sum = started ? sum + term : term;
      started = 1;
    }
  }
  return sum;
}

float ha_state_region_max(const HaAircraftConfig *cfg, const float x[HA_X_DIM]) {
  const uint32_t rows = cfg->sx_rows < HA_SX_MAX_ROWS ? cfg->sx_rows : HA_SX_MAX_ROWS;
  float d[HA_X_DIM];
  float worst = 0.0f; /* an empty region constrains nothing */
  uint32_t i, j;
  /* No clamp here: x comes from ha_state_view, already clamped to the plausibility spans. */
  for (j = 0u; j < HA_X_DIM; ++j) {
    d[j] = is_exact_zero(cfg->x0[j]) ? x[j] : x[j] - cfg->x0[j];
  }
  for (i = 0u; i < rows; ++i) {
    const float value = row_value(cfg->sx[i], d, HA_X_DIM);
    worst = (i == 0u || ha_greater(value, worst)) ? value : worst; /* both finite */
  }
  return worst;
}

float ha_actuator_region_max(const HaAircraftConfig *cfg, const float u[HA_U_DIM]) {
  const uint32_t rows = cfg->su_rows < HA_SU_MAX_ROWS ? cfg->su_rows : HA_SU_MAX_ROWS;
  float d[HA_U_DIM];
  float worst = 0.0f;
  uint32_t i, j;
  for (j = 0u; j < HA_U_DIM; ++j) {
    const float clamped = ha_clampf(u[j], -HA_REGION_SPAN, HA_REGION_SPAN);
    d[j] = is_exact_zero(cfg->u0[j]) ? clamped : clamped - cfg->u0[j];
  }
  for (i = 0u; i < rows; ++i) {
    const float value = row_value(cfg->su[i], d, HA_U_DIM);
    worst = (i == 0u || ha_greater(value, worst)) ? value : worst; /* both finite */
  }
  return worst;
}
