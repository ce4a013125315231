/* The C ground floor as one shared library, libstack_common.so, for Python's ctypes
 * (common/python/stack_common): the geodesy (geo_wgs84) and the ServoCommand/OperatorCommand CRC
 * (hp_command) that the Due and the HP nodes run, so the HiL's verdicts, its sensor model and the
 * flight report compute with the same code, not with a Python copy of it. This file adds only
 * what ctypes cannot reach by itself: the foot behind its macro, the struct's size
 * (to catch a layout that drifted from stack_common.geo), and an array form of the conversion for
 * numpy. */
#include <stddef.h>

#include "geo_wgs84.h"
#include "hp_command.h"

/* The foot as a symbol ctypes can read: stack_common.units defines it in pure Python (the
 * build's generators run before this library exists), and the test holds the two equal. */
const double stack_common_ft_per_m = GEO_FT_PER_M;

size_t stack_common_geo_ref_size(void);
void stack_common_to_ne_ft_n(const GeoRef *ref, size_t n, const double *lat_deg,
                             const double *lon_deg, double *north_ft, double *east_ft);

size_t stack_common_geo_ref_size(void) { return sizeof(GeoRef); }

/* geo_to_neu_ft point by point: a flight log's tens of thousands of fixes in one call, with the
 * same arithmetic as the scalar form. */
void stack_common_to_ne_ft_n(const GeoRef *ref, size_t n, const double *lat_deg,
                             const double *lon_deg, double *north_ft, double *east_ft) {
  size_t i;
  for (i = 0; i < n; ++i) {
    double neu_ft[3];
    geo_to_neu_ft(ref, lat_deg[i], lon_deg[i], ref->alt_m, neu_ft);
    north_ft[i] = neu_ft[0];
    east_ft[i] = neu_ft[1];
  }
}
