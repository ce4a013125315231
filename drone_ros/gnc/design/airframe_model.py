"""Nonlinear rigid-body model of an aircraft built from its airframe.yaml, used to trim and linearise.

The C++ closed-loop test model (drone_ros/controller/test/sim/) implements the same equations
from the same data (through the generated header), so the gains are designed on the plant they
are tested against.
"""
import math

import numpy as np

from stack_tools import check_config  # noqa: E402  (aircraft/schema/: no unknown, missing or mistyped key)

FT_PER_M = 1.0 / 0.3048


def load_airframe(path):
    return check_config.load(path, "airframe")


class Airframe:
    def __init__(self, data):
        self.m = float(data["mass_kg"])
        inertia = data["inertia_kg_m2"]
        self.ixx = float(inertia["ixx"])
        self.iyy = float(inertia["iyy"])
        self.izz = float(inertia["izz"])
        geo = data["geometry"]
        self.s = float(geo["wing_area_m2"])
        self.b = float(geo["wing_span_m"])
        self.c = float(geo["mean_chord_m"])
        self.rho = float(data["air_density_kg_m3"])
        self.g = float(data["gravity_m_s2"])
        self.a = {k: float(v) for k, v in data["aero"].items()}
        prop = data["propulsion"]
        self.t_max = float(prop["max_thrust_n"])
        self.v_zero_thrust = float(prop["zero_thrust_speed_m_s"])

    def body_derivatives(self, x, u):
        """x = [u, v, w, p, q, r, phi, theta, psi] (m/s, rad/s, rad);
        u = [elevator, aileron, rudder, throttle] (rad, rad, rad, 0..1). Still air."""
        ub, vb, wb, p, q, r, phi, theta, _psi = x
        de, da, dr, dt = u
        a = self.a
        vt = math.sqrt(ub * ub + vb * vb + wb * wb)
        alpha = math.atan2(wb, ub)
        beta = math.asin(vb / vt)
        qbar = 0.5 * self.rho * vt * vt
        phat = p * self.b / (2.0 * vt)
        qhat = q * self.c / (2.0 * vt)
        rhat = r * self.b / (2.0 * vt)
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
        lift = qbar * self.s * cl
        drag = qbar * self.s * cd
        thrust = dt * self.t_max * (1.0 - vt / self.v_zero_thrust)
        fx = -drag * math.cos(alpha) + lift * math.sin(alpha) + thrust
        fy = qbar * self.s * cy
        fz = -drag * math.sin(alpha) - lift * math.cos(alpha)
        mx = qbar * self.s * self.b * croll
        my = qbar * self.s * self.c * cm
        mz = qbar * self.s * self.b * cn
        g = self.g
        sphi, cphi = math.sin(phi), math.cos(phi)
        sth, cth = math.sin(theta), math.cos(theta)
        du = r * vb - q * wb + fx / self.m - g * sth
        dv = p * wb - r * ub + fy / self.m + g * sphi * cth
        dw = q * ub - p * vb + fz / self.m + g * cphi * cth
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
