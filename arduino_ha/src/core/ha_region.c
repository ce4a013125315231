#include "ha_region.h"

#include <string.h>

#include "ha_num.h"

/* Actuator values are clamped to +/- this before the product: any real region is far smaller, so
 * the verdict is unchanged, and the sums can neither overflow nor meet inf - inf. */
#define HA_REGION_SPAN 1.0e6f
/* region_max masks a column into its vector: both dimensions must be powers of two. */
typedef char ha_region_dims_are_powers_of_two
    [((HA_X_DIM & (HA_X_DIM - 1)) == 0 && (HA_U_DIM & (HA_U_DIM - 1)) == 0) ? 1 : -1];

/* Exactly +/-0 (integer test on its bits: no soft-float call on the Cortex-M3). A zero centre
 * subtracts nothing, so skipping it changes no result. */
static int is_exact_zero(float c) {
  uint32_t bits;
  memcpy(&bits, &c, sizeof bits);
  return (bits & 0x7FFFFFFFu) == 0u;
}

/* max_i (S d)_i over the rows' nonzero terms (ha_config.h). A row's first term is taken as it is
 * rather than added to 0 (0 + t differs from t only in the sign of a zero), and a row without
 * terms is 0. dim is a power of two: a column is masked into d, not tested. A row end past the
 * table (a hand-made configuration) stops at the table's end. */
static float region_max(const HaRegionTerm *terms, const uint8_t *row_end, uint32_t rows,
                        uint32_t max_terms, const float *d, uint32_t dim) {
  float worst = 0.0f; /* an empty region constrains nothing */
  uint32_t i, k = 0u;
  for (i = 0u; i < rows; ++i) {
    float sum = 0.0f;
    if (k < row_end[i] && k < max_terms) {
      sum = terms[k].coef * d[terms[k].col & (dim - 1u)];
      for (++k; k < row_end[i] && k < max_terms; ++k) {
        sum += terms[k].coef * d[terms[k].col & (dim - 1u)];
      }
    }
    worst = (i == 0u || ha_greater(sum, worst)) ? sum : worst; /* both finite */
  }
  return worst;
}

float ha_state_region_max(const HaAircraftConfig *cfg, const float x[HA_X_DIM]) {
  float d[HA_X_DIM];
  uint32_t j;
  /* No clamp here: x comes from ha_state_view, already clamped to the plausibility spans. */
  for (j = 0u; j < HA_X_DIM; ++j) {
    d[j] = is_exact_zero(cfg->x0[j]) ? x[j] : x[j] - cfg->x0[j];
  }
  return region_max(cfg->sx, cfg->sx_row_end,
                    cfg->sx_rows < HA_SX_MAX_ROWS ? cfg->sx_rows : HA_SX_MAX_ROWS, HA_SX_MAX_TERMS,
                    d, HA_X_DIM);
}

float ha_actuator_region_max(const HaAircraftConfig *cfg, const float u[HA_U_DIM]) {
  float d[HA_U_DIM];
  uint32_t j;
  for (j = 0u; j < HA_U_DIM; ++j) {
    const float clamped = ha_clampf(u[j], -HA_REGION_SPAN, HA_REGION_SPAN);
    d[j] = is_exact_zero(cfg->u0[j]) ? clamped : clamped - cfg->u0[j];
  }
  return region_max(cfg->su, cfg->su_row_end,
                    cfg->su_rows < HA_SU_MAX_ROWS ? cfg->su_rows : HA_SU_MAX_ROWS, HA_SU_MAX_TERMS,
                    d, HA_U_DIM);
}
