"""The stack's one latitude/longitude <-> north/east/up conversion, geo_wgs84.c's: a flat earth on
the WGS84 radii of curvature at a reference point (home), longitude taken the short way round
across the antimeridian. The HiL's verdicts and sensor model and the flight report call it here,
so they place the aircraft where the HA and the controller do."""
import ctypes
import functools

import numpy as np

from .native import GeoRef, library


class Ref:
    """A reference point (home). Raises ValueError for one geo_ref_init refuses: latitude outside
    [-90, 90], longitude outside [-180, 180], altitude outside [-1e4, 1e5] m, NaN anywhere."""

    def __init__(self, lat_deg, lon_deg, alt_m=0.0):
        self._lib = library()
        self._ref = GeoRef()
        if not self._lib.geo_ref_init(ctypes.byref(self._ref), float(lat_deg), float(lon_deg), float(alt_m)):
            raise ValueError("not a reference point geo_ref_init takes: lat %r deg, lon %r deg, alt %r m"
                             % (lat_deg, lon_deg, alt_m))

    def neu_ft(self, lat_deg, lon_deg, alt_m):
        """North, east, up [ft] of a point from the reference."""
        out = (ctypes.c_double * 3)()
        self._lib.geo_to_neu_ft(ctypes.byref(self._ref), float(lat_deg), float(lon_deg), float(alt_m), out)
        return out[0], out[1], out[2]

    def north_east_ft(self, lat_deg, lon_deg):
        """North and east [ft] of a point from the reference."""
        return self.neu_ft(lat_deg, lon_deg, self._ref.alt_m)[:2]

    def north_east_ft_arrays(self, lat_deg, lon_deg):
        """North and east [ft] of arrays of points, as numpy arrays of their shape."""
        lat = np.ascontiguousarray(lat_deg, dtype=np.float64)
        lon = np.ascontiguousarray(lon_deg, dtype=np.float64)
        if lat.shape != lon.shape:
            raise ValueError("latitudes %s and longitudes %s differ in shape" % (lat.shape, lon.shape))
        north, east = np.empty_like(lat), np.empty_like(lat)
        self._lib.stack_common_to_ne_ft_n(ctypes.byref(self._ref), lat.size, lat.ctypes.data, lon.ctypes.data,
                                          north.ctypes.data, east.ctypes.data)
        return north, east

    def from_neu_m(self, north_m, east_m, up_m=0.0):
        """The point (lat, lon, alt) north, east, up [m] of the reference; longitude in [-180, 180]."""
        neu = (ctypes.c_double * 3)(north_m, east_m, up_m)
        lat, lon, alt = ctypes.c_double(), ctypes.c_double(), ctypes.c_double()
        self._lib.geo_from_neu_m(ctypes.byref(self._ref), neu, ctypes.byref(lat), ctypes.byref(lon),
                                 ctypes.byref(alt))
        return lat.value, lon.value, alt.value


@functools.lru_cache(maxsize=64)
def ref(lat_deg, lon_deg, alt_m=0.0):
    """Ref for a home given as numbers, made once per home (a flight asks every step)."""
    return Ref(lat_deg, lon_deg, alt_m)


def north_east_ft(home, lat_deg, lon_deg):
    """North and east [ft] of a point from home = (lat, lon[, alt m])."""
    return ref(*(float(v) for v in home[:2])).north_east_ft(lat_deg, lon_deg)

