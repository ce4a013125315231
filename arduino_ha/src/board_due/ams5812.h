/* AMS 5812 pressure sensor: its I2C reading to differential pressure, and differential
 * pressure to indicated airspeed. Pure C99 so the host can check the arithmetic.
 *
 * From the AMS 5812 datasheet (Analog Microelectronics, "Digital output" and "I2C interface"):
 * a read of 4 bytes returns pressure (MSB, LSB) then temperature (MSB, LSB), each a 15-bit count
 * (the top bit of each MSB is 0). The count spans 3277 (10 % of 2^15) at the part's minimum
 * pressure to 29491 (90 %) at its maximum, linearly; temperature spans the same counts over
 * -25 ... +85 C. */
#ifndef AMS5812_H
#define AMS5812_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define AMS5812_READ_LEN 4u
#define AMS5812_COUNTS_AT_MIN 3277.0f
#define AMS5812_COUNTS_AT_MAX 29491.0f
#define AMS5812_TEMP_MIN_C (-25.0f)
#define AMS5812_TEMP_MAX_C 85.0f

/* Sea-level ISA air density: airspeed from it is indicated airspeed, which is what stall speed
 * is quoted in. */
#define AMS5812_RHO_SEA_LEVEL_KG_M3 1.225f
#define AMS5812_FT_PER_M 3.2808399f

typedef struct {
  float diff_pressure_pa;
  float temperature_c;
} Ams5812Reading;

/* Decodes the 4 bytes of one read for a part spanning [p_min_pa, p_max_pa]. Returns 0 (reading
 * rejected) if a reserved top bit is set (bus floating high) or a count is far below the
 * datasheet's output span (bus stuck low, sensor absent), else 1. */
int ams5812_decode(const uint8_t bytes[AMS5812_READ_LEN], float p_min_pa, float p_max_pa,
                   Ams5812Reading *out);

/* Indicated airspeed from pitot minus static pressure: v = sqrt(2 dp / rho0). A slightly
 * negative dp (sensor offset at rest) reads as 0. */
float ams5812_airspeed_ftps(float diff_pressure_pa);

#ifdef __cplusplus
}
#endif

#endif /* AMS5812_H */
