// Geodetic <-> local North/East conversion: the ONE place microhard_gs turns latitude and
// longitude into feet from home (the `way` message's frame) and back.
#pragma once

namespace microhard_gs {

constexpr double kFeetPerMetre = 1.0 / 0.3048;  // international foot, exact

struct GeoPoint {
  double lat_deg = 0.0;
  double lon_deg = 0.0;
  double alt_m = 0.0;  // WGS84 ellipsoid height, as the INS reports it on /data
};

struct NorthEastFt {
  double north_ft = 0.0;
  double east_ft = 0.0;
};

// Flat-earth (local tangent plane) projection about home using the WGS84 radii of curvature
// at home's latitude: north = dlat * R_meridian, east = dlon * R_prime_vertical * cos(lat).
// Over the few-kilometre radius a mission may span, the error is well under a foot per
// thousand feet, far below GPS accuracy; no trigonometry per waypoint beyond one cos().
NorthEastFt geodetic_to_north_east_ft(const GeoPoint& home, double lat_deg, double lon_deg);

// The inverse of the above, for tests and for reporting local points as lat/lon.
void north_east_ft_to_geodetic(const GeoPoint& home, const NorthEastFt& ne, double* lat_deg,
                               double* lon_deg);

bool is_valid_position(double lat_deg, double lon_deg);
// A home: the HA's own test of the home it latches (geo_ref_init), the one judge of the stack, so
// the ground station neither keeps nor forwards a home the HA would refuse, nor refuses one it
// would keep. Unlike is_valid_position, lat 0 lon 0 is a place here, as it is to the HA.
bool is_valid_home(const GeoPoint& home);

}  // namespace microhard_gs
