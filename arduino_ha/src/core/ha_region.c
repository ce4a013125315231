#include "ha_region.h"

#include "ha_num.h"

/* Values are clamped to +/- this before the product: any real region is far smaller, so the
 * verdict is unchanged, and the sums can neither overflow nor meet inf - inf. */
#define HA_REGION_SPAN 1.0e6f

static float row_value(const float *row, int dim, const float *v, const float *v0) {
  float sum = 0.0f;
  int j;
  for (j = 0; j < dim; ++j) {
    sum += row[j] * (ha_clampf(v[j], -HA_REGION_SPAN, HA_REGION_SPAN) - v0[j]);
  }
  return sum;
}

float ha_state_region_max(const HaAircraftConfig *cfg, const float x[HA_X_DIM]) {
  const uint32_t rows = cfg->sx_rows < HA_SX_MAX_ROWS ? cfg->sx_rows : HA_SX_MAX_ROWS;
  float worst = 0.0f; /* an empty region constrains nothing */
  uint32_t i;
  for (i = 0u; i < rows; ++i) {
    const float value = row_value(cfg->sx[i], HA_X_DIM, x, cfg->x0);
    worst = (i == 0u || value > worst) ? value : worst;
  }
  return worst;
}

float ha_actuator_region_max(const HaAircraftConfig *cfg, const float u[HA_U_DIM]) {
  const uint32_t rows = cfg->su_rows < HA_SU_MAX_ROWS ? cfg->su_rows : HA_SU_MAX_ROWS;
  float worst = 0.0f;
  uint32_t i;
  for (i = 0u; i < rows; ++i) {
    const float value = row_value(cfg->su[i], HA_U_DIM, u, cfg->u0);
    worst = (i == 0u || value > worst) ? value : worst;
  }
  return worst;
}
