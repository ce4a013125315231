"""VN-200 binary output packets built by the C99 encoder (vn200_driver/encode/vn_encode.c,
libvn200_encode.so of the catkin build), one call per packet: the bytes of
vn200_emulation.binary_packet(), which builds them field by field in Python and stays as the
reference test_vn200_encode.py compares these with. The library is found as the dynamic loader
finds it: the devel or install space's lib/ is on LD_LIBRARY_PATH once its setup is sourced."""
import ctypes
import struct

from stack_common import native

# VnSolution of vn_encode.h: the two times, 29 doubles, INS status, satellites, fix, padding.
SOLUTION = struct.Struct("<QQ29dHBB4x")
MAX_PACKET = 751  # VN_BIN_MAX_PACKET
_lib = None


def library():
    """libvn200_encode.so, loaded once; OSError (with what to do) if it was not built."""
    global _lib
    if _lib is None:
        lib = native.load("libvn200_encode.so")
        lib.vn_encode_solution_size.restype = ctypes.c_size_t
        lib.vn_encode_solution_size.argtypes = []
        lib.vn_bin_encode.restype = ctypes.c_size_t
        lib.vn_bin_encode.argtypes = [ctypes.c_uint8, ctypes.c_void_p, ctypes.c_void_p, ctypes.c_void_p,
                                      ctypes.c_size_t]
        if lib.vn_encode_solution_size() != SOLUTION.size:
            raise OSError("libvn200_encode.so's VnSolution is %d bytes, vn200_encode.py packs %d: "
                          "rebuild" % (lib.vn_encode_solution_size(), SOLUTION.size))
        _lib = lib
    return _lib


class PacketEncoder:
    """The packets of one binary output (its groups byte and field masks, indexed by group)."""

    def __init__(self, groups, masks):
        if not 0 <= groups <= 0xFF:
            raise ValueError("groups must be a byte, not %r" % (groups,))
        self.lib = library()
        self.groups = groups
        self.masks = (ctypes.c_uint16 * 6)(*struct.unpack("<6H", struct.pack("<6H", *masks)))
        self.solution = ctypes.create_string_buffer(SOLUTION.size)
        self.out = ctypes.create_string_buffer(MAX_PACKET)

    def packet(self, s):
        """The packet of vn200_emulation.Solution s. Raises ValueError where binary_packet raises
        (a value its field cannot hold: struct.error, OverflowError or a math domain error)."""
        try:
            SOLUTION.pack_into(self.solution, 0, s.startup_ns, s.gps_ns, *s.ypr_deg, *s.rate_radps, *s.lla,
                               *s.vel_ned_mps, *s.accel_mps2, *s.mag_gauss, s.temp_c, s.pressure_kpa,
                               *s.gps_pos_unc_m, s.gps_vel_unc_mps, *s.ypr_unc_deg, s.ins_pos_unc_m,
                               s.ins_vel_unc_mps, s.ins_status, s.num_sats, s.gps_fix)
        except struct.error as e:  # an integer out of its field's range, or a count not of VnSolution's
            raise ValueError(str(e)) from None
        n = self.lib.vn_bin_encode(self.groups, self.masks, self.solution, self.out, MAX_PACKET)
        if n == 0:
            raise ValueError("a value of the solution does not fit its field of the packet")
        return self.out.raw[:n]
