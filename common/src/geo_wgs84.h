/* The ONE latitude/longitude <-> north/east/up conversion of the whole stack: the HA core (Due),
 * the GNC, the VN-200 tf, the ground station, the controller's test model and, through
 * libstack_common.so, the HiL's Python all call this file. It is part of the HA's trusted code:
 * the sketch carries it in src/core and the core's checks (Frama-C EVA, Cortex-M3 size and step
 * cost, branch coverage) take it with the core; HP builds link the CMake target geo_wgs84.
 *
 * A flat earth (local tangent plane) about a reference point, home: north and east are the
 * latitude and longitude differences times the WGS84 meridian radius M and the parallel radius
 * N cos(lat) at the reference latitude, up is the ellipsoid-height difference. Exact at the
 * reference; against the ellipsoid (exact local east/north) the error grows with the square of
 * the distance: at 3000 ft from home, in any direction, 0.25 ft at 45 deg latitude and 0.43 ft at
 * 60 deg (test_geo_wgs84 measures it), far below the INS's own position uncertainty. The float
 * variant the Due uses adds under 0.001 ft there.
 *
 * C99, no heap, no recursion. Callers check inputs (finite, in range) before calling, except
 * geo_ref_init, which checks its own. */
#ifndef GEO_WGS84_H
#define GEO_WGS84_H

#ifdef __cplusplus
extern "C" {
#endif

/* WGS84 (NIMA TR8350.2): semi-major axis, first eccentricity squared. */
#define GEO_WGS84_A_M 6378137.0
#define GEO_WGS84_E2 6.69437999014e-3
#define GEO_FT_PER_M (1.0 / 0.3048) /* international foot, exact */
#define GEO_RAD_PER_DEG 0.017453292519943295769

/* The reference point and the flat earth's scale there, fixed by geo_ref_init. */
typedef struct {
  double lat_deg, lon_deg, alt_m; /* WGS84, ellipsoid height */
  double north_m_per_deg;         /* M * pi/180 */
  double east_m_per_deg;          /* N cos(lat) * pi/180 */
  float north_ft_per_deg_f;       /* the same in ft, single precision, for the Due */
  float east_ft_per_deg_f;
} GeoRef;

/* Meridian (M) and prime-vertical (N) radii of curvature at a latitude in [-90, 90]. */
void geo_radii_m(double lat_deg, double *meridian_m, double *prime_vertical_m);

/* Sets *ref to the point (lat in [-90, 90], lon in [-180, 180], alt in [-1e4, 1e5] m) and
 * returns 1; anything else (NaN included) returns 0 and leaves *ref alone. */
int geo_ref_init(GeoRef *ref, double lat_deg, double lon_deg, double alt_m);

/* Longitude difference lon - ref's, taken the short way round across the antimeridian. */
double geo_dlon_deg(const GeoRef *ref, double lon_deg);

/* North, east, up [m] of a point from the reference. */
void geo_to_neu_m(const GeoRef *ref, double lat_deg, double lon_deg, double alt_m, double neu_m[3]);
/* The same in ft. */
void geo_to_neu_ft(const GeoRef *ref, double lat_deg, double lon_deg, double alt_m,
                   double neu_ft[3]);
/* North and east [ft] in single precision: the differences are taken in double (a float
 * latitude resolves only about a foot), the scaling in float (the Cortex-M3 has no FPU). */
void geo_to_ne_ft_f(const GeoRef *ref, double lat_deg, double lon_deg, float *north_ft,
                    float *east_ft);

/* The inverse: the point north, east, up [m] / [ft] of the reference. Longitude is wrapped into
 * [-180, 180]. */
void geo_from_neu_m(const GeoRef *ref, const double neu_m[3], double *lat_deg, double *lon_deg,
                    double *alt_m);
void geo_from_neu_ft(const GeoRef *ref, const double neu_ft[3], double *lat_deg, double *lon_deg,
                     double *alt_m);

#ifdef __cplusplus
}
#endif

#endif /* GEO_WGS84_H */
