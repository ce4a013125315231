#include "ha_region.h"

#include <string.h>

#include "ha_num.h"

/* Values are clamped to +/- this before the product: any real region is far smaller, so the
 * verdict is unchanged, and the sums can neither overflow nor meet inf - inf. */
#define HA_REGION_SPAN 1.0e6f

/* Coefficient exactly +/-0 (integer test on its bits: no soft-float call on the Cortex-M3). A zero
 * coefficient adds +/-0 to the row, so skipping it changes no result. */
static int coefficient_is_zero(float c) {
  uint32_t bits;
  memcpy(&bits, &c, sizeof bits);
  return (bits & 0x7FFFFFFFu) == 0u;
}

/* Offsets from the region's centre, clamped: computed once per call, not once per row. */
static void offsets(const float *v, const float *v0, uint32_t dim, float *d) {
  uint32_t j;
  for (j = 0u; j < dim; ++j) {
    d[j] = ha_clampf(v[j], -HA_REGION_SPAN, HA_REGION_SPAN) - v0[j];
  }
}

/* One row of S (v - v0). Only nonzero coefficients are multiplied: S_x is sparse (one nonzero
 * per row for a box region), and on the Due every float operation is a library call. */
static float row_value(const float *row, const float *d, uint32_t dim) {
  float sum = 0.0f;
  uint32_t j;
  for (j = 0u; j < dim; ++j) {
    if (!coefficient_is_zero(row[j])) {
      sum += row[j] * d[j];
    }
  }
  return sum;
}

float ha_state_region_max(const HaAircraftConfig *cfg, const float x[HA_X_DIM]) {
  const uint32_t rows = cfg->sx_rows < HA_SX_MAX_ROWS ? cfg->sx_rows : HA_SX_MAX_ROWS;
  float d[HA_X_DIM];
  float worst = 0.0f; /* an empty region constrains nothing */
  uint32_t i;
  offsets(x, cfg->x0, HA_X_DIM, d);
  for (i = 0u; i < rows; ++i) {
    const float value = row_value(cfg->sx[i], d, HA_X_DIM);
    worst = (i == 0u || value > worst) ? value : worst;
  }
  return worst;
}

float ha_actuator_region_max(const HaAircraftConfig *cfg, const float u[HA_U_DIM]) {
  const uint32_t rows = cfg->su_rows < HA_SU_MAX_ROWS ? cfg->su_rows : HA_SU_MAX_ROWS;
  float d[HA_U_DIM];
  float worst = 0.0f;
  uint32_t i;
  offsets(u, cfg->u0, HA_U_DIM, d);
  for (i = 0u; i < rows; ++i) {
    const float value = row_value(cfg->su[i], d, HA_U_DIM);
    worst = (i == 0u || value > worst) ? value : worst;
  }
  return worst;
}
