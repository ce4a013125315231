#include "geo_wgs84.h"

#include <math.h>

/* Bounds of geo_ref_init's altitude: far beyond any INS report, they keep every sum finite. */
#define GEO_MIN_ALT_M (-1.0e4)
#define GEO_MAX_ALT_M 1.0e5
/* Within about 1e-8 deg of a pole east has no usable scale: the inverse keeps the longitude. */
#define GEO_MIN_EAST_M_PER_DEG 1.0e-3

void geo_radii_m(double lat_deg, double *meridian_m, double *prime_vertical_m) {
  const double s = sin(lat_deg * GEO_RAD_PER_DEG);
  const double w2 = 1.0 - GEO_WGS84_E2 * s * s; /* in [1 - e2, 1]: never zero */
  const double w = sqrt(w2);
  *meridian_m = GEO_WGS84_A_M * (1.0 - GEO_WGS84_E2) / (w2 * w);
  *prime_vertical_m = GEO_WGS84_A_M / w;
}

int geo_ref_init(GeoRef *ref, double lat_deg, double lon_deg, double alt_m) {
  double meridian_m;
  double prime_vertical_m;
  double north;
  double east;
  /* The comparisons reject NaN too. */
  if (!(lat_deg >= -90.0 && lat_deg <= 90.0) || !(lon_deg >= -180.0 && lon_deg <= 180.0) ||
      !(alt_m >= GEO_MIN_ALT_M && alt_m <= GEO_MAX_ALT_M)) {
    return 0;
  }
  geo_radii_m(lat_deg, &meridian_m, &prime_vertical_m);
  north = meridian_m * GEO_RAD_PER_DEG;
  east = prime_vertical_m * cos(lat_deg * GEO_RAD_PER_DEG) * GEO_RAD_PER_DEG;
  ref->lat_deg = lat_deg;
  ref->lon_deg = lon_deg;
  ref->alt_m = alt_m;
  ref->north_m_per_deg = north;
  ref->east_m_per_deg = east;
  ref->north_ft_per_deg_f = (float)(north * GEO_FT_PER_M);
  ref->east_ft_per_deg_f = (float)(east * GEO_FT_PER_M);
  return 1;
}

double geo_dlon_deg(const GeoRef *ref, double lon_deg) {
  double d = lon_deg - ref->lon_deg;
  if (d > 180.0) {
    d -= 360.0;
  } else if (d < -180.0) {
    d += 360.0;
  }
  return d;
}

void geo_to_neu_m(const GeoRef *ref, double lat_deg, double lon_deg, double alt_m,
                  double neu_m[3]) {
  neu_m[0] = (lat_deg - ref->lat_deg) * ref->north_m_per_deg;
  neu_m[1] = geo_dlon_deg(ref, lon_deg) * ref->east_m_per_deg;
  neu_m[2] = alt_m - ref->alt_m;
}

void geo_to_neu_ft(const GeoRef *ref, double lat_deg, double lon_deg, double alt_m,
                   double neu_ft[3]) {
  geo_to_neu_m(ref, lat_deg, lon_deg, alt_m, neu_ft);
  neu_ft[0] *= GEO_FT_PER_M;
  neu_ft[1] *= GEO_FT_PER_M;
  neu_ft[2] *= GEO_FT_PER_M;
}

void geo_to_ne_ft_f(const GeoRef *ref, double lat_deg, double lon_deg, float *north_ft,
                    float *east_ft) {
  *north_ft = (float)(lat_deg - ref->lat_deg) * ref->north_ft_per_deg_f;
  *east_ft = (float)geo_dlon_deg(ref, lon_deg) * ref->east_ft_per_deg_f;
}

void geo_from_neu_m(const GeoRef *ref, const double neu_m[3], double *lat_deg, double *lon_deg,
                    double *alt_m) {
  double lon;
  *lat_deg = ref->lat_deg + neu_m[0] / ref->north_m_per_deg;
  /* At a pole east has no scale: the longitude stays the reference's. */
  lon = ref->east_m_per_deg > GEO_MIN_EAST_M_PER_DEG ? ref->lon_deg + neu_m[1] / ref->east_m_per_deg
                                                     : ref->lon_deg;
  if (lon > 180.0) {
    lon -= 360.0;
  } else if (lon < -180.0) {
    lon += 360.0;
  }
  *lon_deg = lon;
  *alt_m = ref->alt_m + neu_m[2];
}

void geo_from_neu_ft(const GeoRef *ref, const double neu_ft[3], double *lat_deg, double *lon_deg,
                     double *alt_m) {
  const double neu_m[3] = {neu_ft[0] / GEO_FT_PER_M, neu_ft[1] / GEO_FT_PER_M,
                           neu_ft[2] / GEO_FT_PER_M};
  geo_from_neu_m(ref, neu_m, lat_deg, lon_deg, alt_m);
}
