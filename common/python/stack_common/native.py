"""The build's C libraries for ctypes, found as the dynamic loader finds them: the devel or
install space's lib/ is on LD_LIBRARY_PATH once its setup is sourced. libstack_common.so is
loaded once, its functions declared."""
import ctypes

_lib = None


class GeoRef(ctypes.Structure):
    """geo_wgs84.h's GeoRef; library() checks its size against the C's."""
    _fields_ = [("lat_deg", ctypes.c_double), ("lon_deg", ctypes.c_double), ("alt_m", ctypes.c_double),
                ("north_m_per_deg", ctypes.c_double), ("east_m_per_deg", ctypes.c_double),
                ("north_ft_per_deg_f", ctypes.c_float), ("east_ft_per_deg_f", ctypes.c_float)]


def _declare(lib):
    d, dp, ref = ctypes.c_double, ctypes.POINTER(ctypes.c_double), ctypes.POINTER(GeoRef)
    for name, restype, argtypes in (
            ("stack_common_geo_ref_size", ctypes.c_size_t, []),
            ("geo_ref_init", ctypes.c_int, [ref, d, d, d]),
            ("geo_to_neu_ft", None, [ref, d, d, d, dp]),
            ("geo_from_neu_m", None, [ref, dp, dp, dp, dp]),
            ("stack_common_to_ne_ft_n", None, [ref, ctypes.c_size_t, ctypes.c_void_p, ctypes.c_void_p,
                                               ctypes.c_void_p, ctypes.c_void_p]),
            ("ha_crc32", ctypes.c_uint32, [ctypes.c_char_p, ctypes.c_size_t])):
        f = getattr(lib, name)
        f.restype, f.argtypes = restype, argtypes


def load(soname):
    """A library of the build, as the dynamic loader finds it; OSError (with what to do) if it
    was not built or the workspace is not sourced."""
    try:
        return ctypes.CDLL(soname)
    except OSError as e:
        raise OSError("%s not found (%s): `make build`, then source the workspace's devel/setup.bash"
                      % (soname, e)) from None


def library():
    """libstack_common.so with its functions declared."""
    global _lib
    if _lib is None:
        lib = load("libstack_common.so")
        _declare(lib)
        if lib.stack_common_geo_ref_size() != ctypes.sizeof(GeoRef):
            raise OSError("libstack_common.so's GeoRef is %d bytes, stack_common's %d: rebuild"
                          % (lib.stack_common_geo_ref_size(), ctypes.sizeof(GeoRef)))
        _lib = lib
    return _lib


def constant(name):
    """A double the library exports (stack_common.c: the foot of geo_wgs84.h)."""
    return ctypes.c_double.in_dll(library(), name).value
