"""Seeded low-altitude turbulence: the Dryden model (MIL-F-8785C / MIL-HDBK-1797, below 1000 ft).

Intensities and scale lengths from the height above ground and the wind speed at 20 ft (W20);
each axis white noise through Dryden's shaping filter with time constant tau = L / V:
longitudinal u: first order, sigma_u sqrt(2 tau / pi) / (1 + tau s); lateral v and vertical w:
sigma sqrt(tau / pi) (1 + sqrt(3) tau s) / (1 + tau s)^2, realised as two first-order lags in
cascade (y1 = n / (1 + tau s), y2 = y1 / (1 + tau s), gust = sqrt(3) y1 + (1 - sqrt(3)) y2), each
lag discretised exactly. Linear gusts only (no rotational p, q, r gusts).

Gusts are generated along the aircraft's heading (longitudinal, lateral, vertical) and returned
in NED, so a turning aircraft meets them as a body-fixed Dryden model would. Deterministic: the
same seed and the same inputs give the same sequence, bit for bit."""
import math

import numpy as np

from stack_common.units import FT_PER_M

KT_TO_MPS = 0.514444
# Wind speed at 20 ft, the low-altitude model's severity parameter (MIL-F-8785C 3.7.2.3).
W20_KT = {"none": 0.0, "light": 15.0, "moderate": 30.0}
SQRT3 = math.sqrt(3.0)
_BLOCK = 4096


class Turbulence:
    def __init__(self, level, seed, dt_s):
        self.w20_mps = W20_KT[level] * KT_TO_MPS
        self.dt_s = dt_s
        self.rng = np.random.Generator(np.random.PCG64(seed))
        self.block = None
        self.i = _BLOCK
        # u; v's and w's two lags, in units of their sigma (so a change of height rescales them).
        self.u = self.v1 = self.v2 = self.w1 = self.w2 = None

    def set_level(self, level):
        """Another severity from now on; the filters' state (in units of sigma) carries on."""
        self.w20_mps = W20_KT[level] * KT_TO_MPS

    def _normals(self):
        if self.i >= _BLOCK:
            self.block = self.rng.standard_normal((_BLOCK, 3)).tolist()
            self.i = 0
        row = self.block[self.i]
        self.i += 1
        return row

    def scales(self, height_agl_m):
        """(sigma_u = sigma_v, sigma_w, L_u = L_v, L_w) in m/s and m at this height."""
        h_ft = min(max(height_agl_m * FT_PER_M, 10.0), 1000.0)
        d = 0.177 + 0.000823 * h_ft
        sigma_w = 0.1 * self.w20_mps
        sigma_u = sigma_w / d ** 0.4
        l_w = h_ft / FT_PER_M
        l_u = h_ft / d ** 1.2 / FT_PER_M
        return sigma_u, sigma_w, l_u, l_w

    def _start(self):
        """Draws the stationary distribution: turbulence is there from the first step.
        Per unit sigma: var(y1) = 1/2, var(y2) = 1/4, cov(y1, y2) = 1/4."""
        n = self._normals() + self._normals()
        half = math.sqrt(0.5)
        eighth = math.sqrt(0.125)
        self.u = n[0]
        self.v1 = half * n[1]
        self.v2 = 0.5 * self.v1 + eighth * n[2]
        self.w1 = half * n[3]
        self.w2 = 0.5 * self.w1 + eighth * n[4]

    def step(self, height_agl_m, airspeed_mps, heading_rad):
        """Advances one dt; returns the gust (north, east, down) in m/s."""
        if self.w20_mps == 0.0:
            return 0.0, 0.0, 0.0
        sigma_u, sigma_w, l_u, l_w = self.scales(height_agl_m)
        if self.u is None:
            self._start()
        else:
            n = self._normals()
            x_u = max(airspeed_mps, 1.0) * self.dt_s / l_u
            x_w = max(airspeed_mps, 1.0) * self.dt_s / l_w
            a_u, a_w = math.exp(-x_u), math.exp(-x_w)
            b_u = math.sqrt(1.0 - a_u * a_u)
            self.u = a_u * self.u + b_u * n[0]
            # Second lag first: it is driven by the first lag's value over the step.
            self.v2 = a_u * self.v2 + x_u * a_u * self.v1
            self.v1 = a_u * self.v1 + b_u * math.sqrt(0.5) * n[1]
            self.w2 = a_w * self.w2 + x_w * a_w * self.w1
            self.w1 = a_w * self.w1 + math.sqrt(1.0 - a_w * a_w) * math.sqrt(0.5) * n[2]
        u = sigma_u * self.u
        v = sigma_u * (SQRT3 * self.v1 + (1.0 - SQRT3) * self.v2)
        w = sigma_w * (SQRT3 * self.w1 + (1.0 - SQRT3) * self.w2)
        c, s = math.cos(heading_rad), math.sin(heading_rad)
        return u * c - v * s, u * s + v * c, w
