#!/usr/bin/env python3
"""Trims and linearises the DG808 airframe model and writes the LQR inner-loop gains.

Usage: design_gains.py [--out PATH]   (default: ../gnc/dg808_gnc_data.h, the checked-in header)

Reads airframe.yaml (the model) and controller_param.yaml (Q_weight, dt) of this aircraft, and
writes one C header with the airframe constants, the design trim and the gains, so the GNC and
its closed-loop test model use exactly what the gains were designed on. The output is
deterministic: numbers are rounded to 9 significant digits, so a rerun with the pinned scipy
reproduces the checked-in file byte for byte (drone_ros/controller/test checks it).
"""
import argparse
import hashlib
import os
import sys

import numpy as np
import scipy.linalg
import scipy.optimize

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
HERE = os.path.dirname(os.path.abspath(__file__))
AIRCRAFT_DIR = os.path.dirname(HERE)
from airframe_model import Airframe, FT_PER_M, check_config, load_airframe  # noqa: E402

# Bryson's rule: the largest deviation we accept of each state and input. The LQR weight of a
# quantity is 1/max^2; Q_weight from controller_param.yaml scales the state weights.
LON_STATE_MAX = [3.0, 0.10, 0.5, 0.10, 4.0, 0.2]   # dV m/s, dalpha, q, dtheta, int eV m, int etheta rad s
LON_INPUT_MAX = [0.12, 0.5]                         # elevator rad, throttle
LAT_STATE_MAX = [0.08, 1.0, 0.5, 0.15, 0.4]        # beta, p, r, phi, int ephi rad s
LAT_INPUT_MAX = [0.15, 0.15]                        # aileron rad, rudder rad


def num(value):
    """Deterministic text for a double: 9 significant digits, C literal."""
    text = "%.9g" % (value + 0.0)  # + 0.0 turns -0.0 into 0.0
    return text if ("." in text or "e" in text) else text + ".0"


def trim(af, vt):
    """Level wings-level flight at vt: solves for alpha, elevator, throttle."""
    def residual(z):
        alpha, de, dt = z
        xs = np.array([vt, alpha, 0.0, 0.0, 0.0, 0.0, 0.0, alpha])
        d = af.wind_axes_derivatives(xs, [de, 0.0, 0.0, dt])
        return [d[0], d[1], d[4]]
    sol, _info, ier, msg = scipy.optimize.fsolve(residual, [0.05, 0.0, 0.3], full_output=True,
                                                  xtol=1e-13)
    if ier != 1:
        raise SystemExit("trim failed: " + msg)
    return sol


def jacobians(af, x0, u0):
    n, m = len(x0), len(u0)
    a = np.zeros((n, n))
    b = np.zeros((n, m))
    for i in range(n):
        h = 1e-6
        xp, xm = x0.copy(), x0.copy()
        xp[i] += h
        xm[i] -= h
        a[:, i] = (af.wind_axes_derivatives(xp, u0) - af.wind_axes_derivatives(xm, u0)) / (2 * h)
    for j in range(m):
        h = 1e-6
        up, um = list(u0), list(u0)
        up[j] += h
        um[j] -= h
        b[:, j] = (af.wind_axes_derivatives(x0, up) - af.wind_axes_derivatives(x0, um)) / (2 * h)
    return a, b


def lqr(a, b, state_max, input_max, q_weight):
    q = np.diag([q_weight / (s * s) for s in state_max])
    r = np.diag([1.0 / (s * s) for s in input_max])
    p = scipy.linalg.solve_continuous_are(a, b, q, r)
    return np.linalg.solve(r, b.T @ p)


def check_discrete(a, b, k, dt, name):
    """The gains run in a sampled loop: the zero-order-hold closed loop must be stable."""
    n = a.shape[0]
    m = b.shape[1]
    big = np.zeros((n + m, n + m))
    big[:n, :n] = a
    big[:n, n:] = b
    e = scipy.linalg.expm(big * dt)
    ad, bd = e[:n, :n], e[:n, n:]
    radius = max(abs(np.linalg.eigvals(ad - bd @ k)))
    if radius >= 1.0:
        raise SystemExit("%s loop unstable at dt=%g s (spectral radius %g)" % (name, dt, radius))
    return radius


def design(af, data, q_weight, dt_max):
    """The design trim, the LQR gains of both axes and their worst sampled-loop spectral radii."""
    vt = float(data["design_point"]["airspeed_ftps"]) / FT_PER_M
    alpha, de, dt = trim(af, vt)
    x0 = np.array([vt, alpha, 0.0, 0.0, 0.0, 0.0, 0.0, alpha])
    u0 = [de, 0.0, 0.0, dt]
    a, b = jacobians(af, x0, u0)

    # Longitudinal: x = [V, alpha, q, theta], u = [elevator, throttle], plus integrals of the
    # airspeed and pitch tracking errors so steady winds and trim errors leave no offset.
    lon = [0, 1, 4, 7]
    a_lon = a[np.ix_(lon, lon)]
    b_lon = b[np.ix_(lon, [0, 3])]
    c_lon = np.array([[1.0, 0, 0, 0], [0, 0, 0, 1.0]])
    a_lon_aug = np.block([[a_lon, np.zeros((4, 2))], [c_lon, np.zeros((2, 2))]])
    b_lon_aug = np.vstack([b_lon, np.zeros((2, 2))])
    k_lon = lqr(a_lon_aug, b_lon_aug, LON_STATE_MAX, LON_INPUT_MAX, q_weight)

    # Lateral-directional: x = [beta, p, r, phi], u = [aileron, rudder], plus the roll error integral.
    lat = [2, 3, 5, 6]
    a_lat = a[np.ix_(lat, lat)]
    b_lat = b[np.ix_(lat, [1, 2])]
    c_lat = np.array([[0, 0, 0, 1.0]])
    a_lat_aug = np.block([[a_lat, np.zeros((4, 1))], [c_lat, np.zeros((1, 1))]])
    b_lat_aug = np.vstack([b_lat, np.zeros((1, 2))])
    k_lat = lqr(a_lat_aug, b_lat_aug, LAT_STATE_MAX, LAT_INPUT_MAX, q_weight)

    # 100 Hz is the fastest rate the node allows; dt is the slowest the parameters allow.
    rho_lon = max(check_discrete(a_lon_aug, b_lon_aug, k_lon, h, "longitudinal") for h in (0.01, dt_max))
    rho_lat = max(check_discrete(a_lat_aug, b_lat_aug, k_lat, h, "lateral") for h in (0.01, dt_max))
    return dict(vt=vt, alpha=alpha, de=de, dt=dt, k_lon=k_lon, k_lat=k_lat, rho_lon=rho_lon,
                rho_lat=rho_lat)


def matrix_lines(name, k):
    """A gain matrix as the header declares it: its size, then its rows."""
    rows, cols = len(k), len(k[0])
    return (["#define %s_ROWS %d" % (name, rows), "#define %s_COLS %d" % (name, cols),
             "static const double %s[%d][%d] = {" % (name, rows, cols)]
            + ["  {" + ", ".join(num(v) for v in row) + "}," for row in k] + ["};"])


def header_text(af, g, q_weight, airframe_sha):
    """dg808_gnc_data.h: the airframe's constants, the design trim and the gains g."""
    lines = []
    w = lines.append
    w("/* GENERATED by aircraft/DG808/design/design_gains.py from airframe.yaml and")
    w(" * controller_param.yaml. Do not edit: change the data and rerun the script.")
    w(" * airframe.yaml sha256: %s */" % airframe_sha)
    w("#ifndef DG808_GNC_DATA_H")
    w("#define DG808_GNC_DATA_H")
    w("")
    w("/* Airframe (SI, body FRD). */")
    consts = [
        ("MASS_KG", af.m), ("IXX_KG_M2", af.ixx), ("IYY_KG_M2", af.iyy), ("IZZ_KG_M2", af.izz),
        ("WING_AREA_M2", af.s), ("WING_SPAN_M", af.b), ("MEAN_CHORD_M", af.c),
        ("AIR_DENSITY_KG_M3", af.rho), ("GRAVITY_M_S2", af.g),
        ("MAX_THRUST_N", af.t_max), ("ZERO_THRUST_SPEED_M_S", af.v_zero_thrust),
    ]
    for key in sorted(af.a):
        consts.append((key.upper(), af.a[key]))
    for name, value in consts:
        w("#define DG808_%s (%s)" % (name, num(value)))
    w("")
    w("/* Design trim: level flight at the design airspeed. */")
    w("#define DG808_TRIM_AIRSPEED_M_S (%s)" % num(g["vt"]))
    w("#define DG808_TRIM_ALPHA_RAD (%s)" % num(g["alpha"]))
    w("#define DG808_TRIM_THETA_RAD (%s)" % num(g["alpha"]))
    w("#define DG808_TRIM_ELEVATOR_RAD (%s)" % num(g["de"]))
    w("#define DG808_TRIM_THROTTLE (%s)" % num(g["dt"]))
    w("")
    w("/* LQR weights used (controller_param.yaml Q_weight) and the worst sampled-loop spectral")
    w(" * radius over 100 Hz and dt: lon %s, lat %s. */" % (num(g["rho_lon"]), num(g["rho_lat"])))
    w("#define DG808_DESIGN_Q_WEIGHT (%s)" % num(q_weight))
    w("")
    w("/* u_lon = [elevator rad, throttle] = trim - K_LON * [dV m/s, dalpha rad, q rad/s,")
    w(" *          dtheta rad, integral(V - V_cmd) m, integral(theta - theta_cmd) rad s] */")
    lines.extend(matrix_lines("DG808_K_LON", g["k_lon"]))
    w("")
    w("/* u_lat = [aileron rad, rudder rad] = -K_LAT * [beta rad, p rad/s, r rad/s, dphi rad,")
    w(" *          integral(phi - phi_cmd) rad s] */")
    lines.extend(matrix_lines("DG808_K_LAT", g["k_lat"]))
    w("")
    w("#endif /* DG808_GNC_DATA_H */")
    return "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=os.path.join(AIRCRAFT_DIR, "gnc", "dg808_gnc_data.h"))
    args = parser.parse_args()

    airframe_path = os.path.join(AIRCRAFT_DIR, "airframe.yaml")
    params_path = os.path.join(AIRCRAFT_DIR, "controller_param.yaml")
    data = load_airframe(airframe_path)
    params = check_config.load(params_path, "controller_param")
    q_weight = float(params["Q_weight"])
    dt_max = float(params["dt"])
    af = Airframe(data)

    g = design(af, data, q_weight, dt_max)
    with open(airframe_path, "rb") as f:
        airframe_sha = hashlib.sha256(f.read()).hexdigest()

    text = header_text(af, g, q_weight, airframe_sha)
    with open(args.out, "w", encoding="utf-8", newline="\n") as f:
        f.write(text)
    print("trim: V=%.3f m/s alpha=%.4f rad elevator=%.4f rad throttle=%.4f"
          % (g["vt"], g["alpha"], g["de"], g["dt"]))
    print("wrote %s" % args.out)


if __name__ == "__main__":
    main()
