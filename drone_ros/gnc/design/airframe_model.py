"""Nonlinear rigid-body model of an aircraft built from its airframe.yaml, used to trim and linearise.

The C++ closed-loop test model (drone_ros/controller/test/sim/) implements the same equations
from the same data (through the generated header), so the gains are designed on the plant they
are tested against.
"""
import math

import numpy as np

from stack_tools import check_config  # noqa: E402  (aircraft/schema/: no unknown, missing or mistyped key)
from stack_tools.airframe_body import AirframeBody

FT_PER_M = 1.0 / 0.3048


def load_airframe(path):
    return check_config.load(path, "airframe")


class Airframe(AirframeBody):
    """The equations of motion on airframe.yaml's body, in its design atmosphere (still air)."""

    def body_derivatives(self, x, u):
        """x = [u, v, w, p, q, r, phi, theta, psi] (m/s, rad/s, rad);
        u = [elevator, aileron, rudder, throttle] (rad, rad, rad, 0..1). Still air."""
        ub, vb, wb, p, q, r, phi, theta, _psi = x
        de, da, dr, dt = u
        a = self.aero
        m, s, b, c = self.mass_kg, self.wing_area_m2, self.span_m, self.chord_m
        vt = math.sqrt(ub * ub + vb * vb + wb * wb)
        alpha = math.atan2(wb, ub)
        beta = math.asin(vb / vt)
        qbar = 0.5 * self.design_air_density_kg_m3 * vt * vt
        phat = p * b / (2.0 * vt)
        qhat = q * c / (2.0 * vt)
        rhat = r * b / (2.0 * vt)
        cl = a["cl0"] + a["cl_alpha_per_rad"] * alpha + a["cl_q_per_rad"] * qhat \
            + a["cl_elevator_per_rad"] * de
        cd = a["cd0"] + a["cd_k"] * cl * cl
        cy = a["cy_beta_per_rad"] * beta + a["cy_rudder_per_rad"] * dr
        croll = a["cl_beta_per_rad"] * beta + a["cl_p_per_rad"] * phat + a["cl_r_per_rad"] * rhat \
            + a["cl_aileron_per_rad"] * da + a["cl_rudder_per_rad"] * dr
        cm = a["cm0"] + a["cm_alpha_per_rad"] * alpha + a["cm_q_per_rad"] * qhat \
            + a["cm_elevator_per_rad"] * de
        cn = a["cn_beta_per_rad"] * beta + a["cn_p_per_rad"] * phat + a["cn_r_per_rad"] * rhat \
            + a["cn_aileron_per_rad"] * da + a["cn_rudder_per_rad"] * dr
        lift = qbar * s * cl
        drag = qbar * s * cd
        thrust = dt * self.max_thrust_n * (1.0 - vt / self.zero_thrust_speed_mps)
        fx = -drag * math.cos(alpha) + lift * math.sin(alpha) + thrust
        fy = qbar * s * cy
        fz = -drag * math.sin(alpha) - lift * math.cos(alpha)
        mx = qbar * s * b * croll
        my = qbar * s * c * cm
        mz = qbar * s * b * cn
        g = self.design_gravity_m_s2
        sphi, cphi = math.sin(phi), math.cos(phi)
        sth, cth = math.sin(theta), math.cos(theta)
        du = r * vb - q * wb + fx / m - g * sth
        dv = p * wb - r * ub + fy / m + g * sphi * cth
        dw = q * ub - p * vb + fz / m + g * cphi * cth
        dp = (mx + (self.iyy - self.izz) * q * r) / self.ixx
        dq = (my + (self.izz - self.ixx) * p * r) / self.iyy
        dr_ = (mz + (self.ixx - self.iyy) * p * q) / self.izz
        dphi = p + math.tan(theta) * (q * sphi + r * cphi)
        dtheta = q * cphi - r * sphi
        dpsi = (q * sphi + r * cphi) / cth
        return np.array([du, dv, dw, dp, dq, dr_, dphi, dtheta, dpsi])

    def wind_axes_derivatives(self, xs, u):
        """xs = [V, alpha, beta, p, q, r, phi, theta]: the states the inner loops feed back."""
        vt, alpha, beta, p, q, r, phi, theta = xs
        ub = vt * math.cos(alpha) * math.cos(beta)
        vb = vt * math.sin(beta)
        wb = vt * math.sin(alpha) * math.cos(beta)
        d = self.body_derivatives(np.array([ub, vb, wb, p, q, r, phi, theta, 0.0]), u)
        du, dv, dw = d[0], d[1], d[2]
        dvt = (ub * du + vb * dv + wb * dw) / vt
        dalpha = (ub * dw - wb * du) / (ub * ub + wb * wb)
        dbeta = (vt * dv - vb * dvt) / (vt * vt * math.cos(beta))
        return np.array([dvt, dalpha, dbeta, d[3], d[4], d[5], d[6], d[7]])
