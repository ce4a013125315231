"""The simulator's per-step ROS I/O in lockstep, by a roscpp node inside its process
(hil/native/lockstep_io.cpp, libhil_lockstep_io.so through ctypes): /clock and /hil/lockstep
published, and the topics the step waits for counted as they arrive, without being decoded and
without a Python thread to wake. A call that waits lets go of the GIL while it waits (ctypes does
for every call), so the rospy threads that remain run meanwhile.

The node is named after the simulator with `_io` appended, in its namespace: the graph checks of
the preflight ask it, not the rospy node, about the connections it owns (LockstepIo.name)."""
import ctypes

import rospy

from stack_common import native

# hil/native/lockstep_io.cpp's Counted, by the keys hil.sim.Waiter counts them under; "to_hil",
# the controller's guidance record, is not waited for: its waypoint changes are kept (waypoints()).
KEYS = ("vn", "status", "pwm", "home", "servo_op", "to_hil")


def library():
    lib = native.load("libhil_lockstep_io.so")
    u64, c_int, dbl = ctypes.c_uint64, ctypes.c_int, ctypes.c_double
    for name, restype, argtypes in (
            ("hio_init", c_int, [ctypes.c_char_p, ctypes.c_char_p, ctypes.POINTER(ctypes.c_char_p)]),
            ("hio_count", u64, [c_int]),
            ("hio_wait_count", c_int, [c_int, u64, dbl]),
            ("hio_latest", ctypes.c_size_t, [c_int, ctypes.c_void_p, ctypes.c_size_t]),
            ("hio_publish_step", c_int, [u64, ctypes.POINTER(ctypes.c_uint32)]),
            ("hio_waypoints", ctypes.c_size_t, [ctypes.POINTER(u64), ctypes.POINTER(ctypes.c_int32), ctypes.c_size_t]),
            ("hio_shutdown", None, [])):
        f = getattr(lib, name)
        f.restype, f.argtypes = restype, argtypes
    return lib


class LockstepIo:
    """topics: {key: resolved topic name} for each of KEYS."""

    def __init__(self, topics):
        self.lib = library()
        self.index = {k: i for i, k in enumerate(KEYS)}
        self.keys = frozenset(KEYS)
        ns = rospy.get_namespace()
        self.name = ns.rstrip("/") + "/" + rospy.get_name().rsplit("/", 1)[-1] + "_io"
        names = (ctypes.c_char_p * len(KEYS))(*(topics[k].encode() for k in KEYS))
        if not self.lib.hio_init(ns.encode(), self.name.rsplit("/", 1)[-1].encode(), names):
            raise RuntimeError("libhil_lockstep_io: its node is already up in this process")
        self.declared = (ctypes.c_uint32 * 9)()
        self.buf = ctypes.create_string_buffer(64)  # grown by _latest_bytes() if a message needs more

    def count(self, key):
        return self.lib.hio_count(self.index[key])

    def wait_count(self, key, at_least, timeout_s):
        """Whether `at_least` messages of key have arrived, waiting up to timeout_s for them."""
        return bool(self.lib.hio_wait_count(self.index[key], at_least, timeout_s))

    def latest(self, key, msg_class):
        """The newest message of key, decoded as msg_class (None before the first)."""
        b = self._latest_bytes(key)
        return msg_class().deserialize(b) if b else None

    def _latest_bytes(self, key):
        """The newest message of key as serialized (b"" before the first)."""
        n = self.lib.hio_latest(self.index[key], self.buf, len(self.buf))
        if n > len(self.buf):  # a bigger one than any before: room for it, and ask again
            self.buf = ctypes.create_string_buffer(2 * n)
            n = self.lib.hio_latest(self.index[key], self.buf, len(self.buf))
        return self.buf.raw[:n]

    def latest_seq(self, key):
        """The first field of the newest message of key, a uint32 (ServoCommand.seq; None
        before the first), read without decoding the rest."""
        b = self._latest_bytes(key)
        return int.from_bytes(b[:4], "little") if len(b) >= 4 else None

    def waypoints(self):
        """[(t_s, waypoint index)] at each change of the controller's guidance (/to_hil), t_s the
        controller step's stamp."""
        n = self.lib.hio_waypoints(None, None, 0)
        stamps, indexes = (ctypes.c_uint64 * n)(), (ctypes.c_int32 * n)()
        n = min(n, self.lib.hio_waypoints(stamps, indexes, n))
        return [(round(stamps[i] / 1e6, 3), int(indexes[i])) for i in range(n)]

    def publish_step(self, t_us, declared):
        """/clock to t_us, then /hil/lockstep with declared: the nine counts in LockstepStep's order."""
        self.declared[:] = declared
        self.lib.hio_publish_step(t_us, self.declared)

    def close(self):
        self.lib.hio_shutdown()
