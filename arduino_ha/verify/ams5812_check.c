/* Host check of the Due's AMS 5812 arithmetic (src/board_due/ams5812.c) against values worked out
 * by hand from the datasheet's transfer function for the fitted part (0 ... 2068.43 Pa):
 * counts 3277 -> 0 Pa, 29491 -> 2068.43 Pa, linear between; v = sqrt(2 dp / 1.225) m/s. Run by
 * board_compile_check.sh; exits non-zero with the failing story's name. */
#include <math.h>
#include <stdio.h>

#include "ams5812.h"

#define P_MAX_PA 2068.43f

static int failures = 0;

static void expect_near(const char *story, double got, double want, double tol) {
  if (!(fabs(got - want) <= tol)) {
    printf("FAIL %s: got %.4f, want %.4f +/- %.4f\n", story, got, want, tol);
    ++failures;
  }
}

static int decode(unsigned p_counts, unsigned t_counts, Ams5812Reading *r) {
  const uint8_t bytes[4] = {(uint8_t)(p_counts >> 8), (uint8_t)(p_counts & 0xFFu),
                            (uint8_t)(t_counts >> 8), (uint8_t)(t_counts & 0xFFu)};
  return ams5812_decode(bytes, 0.0f, P_MAX_PA, r);
}

int main(void) {
  Ams5812Reading r;
  /* 10 % point: zero pressure, still air. */
  if (!decode(3277u, 3277u, &r)) {
    printf("FAIL ZeroPressureCountsAreAReading\n");
    ++failures;
  }
  expect_near("ZeroPressureReadsZeroAirspeed", ams5812_airspeed_ftps(r.diff_pressure_pa), 0.0,
              1e-3);
  expect_near("TenPercentCountsAreMinusTwentyFiveC", r.temperature_c, -25.0, 1e-3);
  /* 90 % point: full scale, 2068.43 Pa -> 58.112 m/s = 190.66 ft/s. */
  (void)decode(29491u, 29491u, &r);
  expect_near("FullScaleCountsAreFullScalePressure", r.diff_pressure_pa, 2068.43, 0.01);
  expect_near("FullScalePressureReads190Ftps", ams5812_airspeed_ftps(r.diff_pressure_pa), 190.66,
              0.05);
  expect_near("NinetyPercentCountsAreEightyFiveC", r.temperature_c, 85.0, 1e-3);
  /* Mid scale: 16384 counts -> 1034.24 Pa -> 41.09 m/s = 134.82 ft/s. */
  (void)decode(16384u, 16384u, &r);
  expect_near("MidScaleCountsAreHalfPressure", r.diff_pressure_pa, 1034.24, 0.05);
  expect_near("MidScalePressureReads135Ftps", ams5812_airspeed_ftps(r.diff_pressure_pa), 134.82,
              0.05);
  /* Offset below zero at rest reads 0, never NaN. */
  (void)decode(3200u, 16384u, &r);
  expect_near("NegativeOffsetReadsZeroAirspeed", ams5812_airspeed_ftps(r.diff_pressure_pa), 0.0,
              0.0);
  /* Bus floating high (0xFF bytes) and bus stuck low (0x00) are rejected. */
  if (decode(0xFFFFu, 0xFFFFu, &r) || decode(0u, 0u, &r)) {
    printf("FAIL FloatingOrStuckBusIsRejected\n");
    ++failures;
  }
  if (failures == 0) {
    printf("ams5812_check: 10 checks passed\n");
  }
  return failures == 0 ? 0 : 1;
}
