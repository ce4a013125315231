"""Seeded low-altitude turbulence: Dryden intensities and scale lengths (MIL-F-8785C / MIL-HDBK-1797
below 1000 ft), each axis a first-order Gauss-Markov process with the Dryden time constant L/V
(the Dryden u spectrum exactly; v and w get first-order rather than Dryden's second-order shape).

Gusts are generated along the aircraft's heading (longitudinal, lateral, vertical) and returned
in NED, so a turning aircraft meets them as a body-fixed Dryden model would. Deterministic: the
same seed and the same inputs give the same sequence, bit for bit."""
import math

import numpy as np

FT_PER_M = 1.0 / 0.3048
KT_TO_MPS = 0.514444
# Wind speed at 20 ft, the low-altitude model's severity parameter (MIL-F-8785C 3.7.2.3).
W20_KT = {"none": 0.0, "light": 15.0, "moderate": 30.0}
_BLOCK = 4096


class Turbulence:
    def __init__(self, level, seed, dt_s):
        self.w20_mps = W20_KT[level] * KT_TO_MPS
        self.dt_s = dt_s
        self.rng = np.random.Generator(np.random.PCG64(seed))
        self.block = None
        self.i = _BLOCK
        self.state = None   # (u, v, w) gusts along heading, right, down [m/s]

    def _normals(self):
        if self.i >= _BLOCK:
            self.block = self.rng.standard_normal((_BLOCK, 3)).tolist()
            self.i = 0
        row = self.block[self.i]
        self.i += 1
        return row

    def _scales(self, height_agl_m):
        h_ft = min(max(height_agl_m * FT_PER_M, 10.0), 1000.0)
        d = 0.177 + 0.000823 * h_ft
        sigma_w = 0.1 * self.w20_mps
        sigma_u = sigma_w / d ** 0.4
        l_w = h_ft / FT_PER_M
        l_u = h_ft / d ** 1.2 / FT_PER_M
        return sigma_u, sigma_w, l_u, l_w

    def step(self, height_agl_m, airspeed_mps, heading_rad):
        """Advances one dt; returns the gust (north, east, down) in m/s."""
        if self.w20_mps == 0.0:
            return 0.0, 0.0, 0.0
        sigma_u, sigma_w, l_u, l_w = self._scales(height_agl_m)
        n = self._normals()
        if self.state is None:
            # Start in the stationary distribution: turbulence is there from the first step.
            u, v, w = sigma_u * n[0], sigma_u * n[1], sigma_w * n[2]
        else:
            v_mps = max(airspeed_mps, 1.0)
            a_u = math.exp(-v_mps * self.dt_s / l_u)
            a_w = math.exp(-v_mps * self.dt_s / l_w)
            b_u = sigma_u * math.sqrt(1.0 - a_u * a_u)
            b_w = sigma_w * math.sqrt(1.0 - a_w * a_w)
            u0, v0, w0 = self.state
            u = a_u * u0 + b_u * n[0]
            v = a_u * v0 + b_u * n[1]
            w = a_w * w0 + b_w * n[2]
        self.state = (u, v, w)
        c, s = math.cos(heading_rad), math.sin(heading_rad)
        return u * c - v * s, u * s + v * c, w
