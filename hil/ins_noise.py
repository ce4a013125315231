"""The navigation filter's Gauss-Markov errors drawn in C (hil/native/ins_noise.c,
libhil_ins_noise.so through ctypes): CPython's random.Random and random.gauss to the bit, from the
generator's state handed over, so a seed gives the numbers it gave when Python drew them."""
import ctypes

from stack_common import native

CHANNELS = 9
_MT_WORDS = 624
_lib = None


def library():
    global _lib
    if _lib is None:
        lib = native.load("libhil_ins_noise.so")
        i64, dp, vp = ctypes.c_int64, ctypes.POINTER(ctypes.c_double), ctypes.c_void_p
        for name, restype, argtypes in (
                ("ins_noise_size", ctypes.c_size_t, []),
                ("ins_noise_keep", ctypes.c_int, []),
                ("ins_noise_init", ctypes.c_int, [vp, ctypes.POINTER(ctypes.c_uint32), ctypes.c_int32,
                                                  ctypes.c_int32, ctypes.c_double, dp, dp, dp]),
                ("ins_noise_start", None, [vp, i64]),
                ("ins_noise_draw_to", None, [vp, i64]),
                ("ins_noise_at", ctypes.c_int, [vp, i64, dp]),
                ("ins_noise_normals", None, [vp, ctypes.c_size_t, dp]),
                ("ins_noise_state", None, [vp, ctypes.POINTER(ctypes.c_uint32), ctypes.POINTER(ctypes.c_int32),
                                           ctypes.POINTER(ctypes.c_int32), dp])):
            f = getattr(lib, name)
            f.restype, f.argtypes = restype, argtypes
        _lib = lib
    return _lib


class InsNoise:
    """Nine processes x' = a x + k z on a grid, z the unit normals rng would draw next. rng is
    not drawn from afterwards: its state is this object's now (random_state() gives it back)."""

    def __init__(self, rng, a, k, x):
        lib = library()
        self.lib = lib
        self.keep = lib.ins_noise_keep()
        self.state = ctypes.create_string_buffer(lib.ins_noise_size())
        _, words, gauss_next = rng.getstate()
        nine = ctypes.c_double * CHANNELS
        if not lib.ins_noise_init(self.state, (ctypes.c_uint32 * _MT_WORDS)(*words[:_MT_WORDS]), words[_MT_WORDS],
                                  gauss_next is not None, 0.0 if gauss_next is None else gauss_next,
                                  nine(*a), nine(*k), nine(*x)):
            raise ValueError("not a random.Random state: position %r" % (words[_MT_WORDS],))
        self.out = nine()

    def start(self, index):
        """The grid begins at index with the initial values."""
        self.lib.ins_noise_start(self.state, index)

    def draw_to(self, index):
        self.lib.ins_noise_draw_to(self.state, index)

    def at(self, index):
        """The nine values at a grid index among the last `keep` drawn (IndexError for another)."""
        if not self.lib.ins_noise_at(self.state, index, self.out):
            raise IndexError("grid index %d is not among the last %d drawn" % (index, self.keep))
        return self.out[:]

    def normals(self, n):
        """The next n unit normals, as rng.gauss(0.0, 1.0) would give them."""
        out = (ctypes.c_double * n)()
        self.lib.ins_noise_normals(self.state, n, out)
        return out[:]

    def random_state(self):
        """random.Random.getstate() of the generator where it stands now."""
        words = (ctypes.c_uint32 * _MT_WORDS)()
        pos, cached_flag, cached = ctypes.c_int32(), ctypes.c_int32(), ctypes.c_double()
        self.lib.ins_noise_state(self.state, words, ctypes.byref(pos), ctypes.byref(cached_flag), ctypes.byref(cached))
        return 3, tuple(words) + (pos.value,), cached.value if cached_flag.value else None
