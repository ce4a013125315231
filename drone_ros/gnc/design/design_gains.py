#!/usr/bin/env python3
"""Trims and linearises an aircraft's airframe model and writes its LQR inner-loop gains.

Usage: design_gains.py aircraft/<name> [--out PATH]   (default: aircraft/<name>/gains.yaml)

Reads the aircraft's airframe.yaml (the model) and controller_param.yaml (Q_weight, dt) and
writes gains.yaml: the design trim and the gains, with the airframe's sha256 they were designed
on. The build makes the GNC's header from gains.yaml and airframe.yaml together, so the GNC and
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


def loop_models(a, b):
    """The two inner loops' plants (A, B) from the airframe's linearisation, each with the
    integrals of its tracked errors appended to the state (the gains' column order)."""
    # Longitudinal: x = [V, alpha, q, theta], u = [elevator, throttle], plus integrals of the
    # airspeed and pitch tracking errors so steady winds and trim errors leave no offset.
    lon = [0, 1, 4, 7]
    c_lon = np.array([[1.0, 0, 0, 0], [0, 0, 0, 1.0]])
    a_lon = np.block([[a[np.ix_(lon, lon)], np.zeros((4, 2))], [c_lon, np.zeros((2, 2))]])
    b_lon = np.vstack([b[np.ix_(lon, [0, 3])], np.zeros((2, 2))])
    # Lateral-directional: x = [beta, p, r, phi], u = [aileron, rudder], plus the roll error integral.
    lat = [2, 3, 5, 6]
    c_lat = np.array([[0, 0, 0, 1.0]])
    a_lat = np.block([[a[np.ix_(lat, lat)], np.zeros((4, 1))], [c_lat, np.zeros((1, 1))]])
    b_lat = np.vstack([b[np.ix_(lat, [1, 2])], np.zeros((1, 2))])
    return (a_lon, b_lon), (a_lat, b_lat)


def design(af, data, q_weight, dt_max):
    """The design trim, the LQR gains of both axes and their worst sampled-loop spectral radii."""
    vt = float(data["design_point"]["airspeed_ftps"]) / FT_PER_M
    alpha, de, dt = trim(af, vt)
    x0 = np.array([vt, alpha, 0.0, 0.0, 0.0, 0.0, 0.0, alpha])
    u0 = [de, 0.0, 0.0, dt]
    a, b = jacobians(af, x0, u0)

    (a_lon_aug, b_lon_aug), (a_lat_aug, b_lat_aug) = loop_models(a, b)
    k_lon = lqr(a_lon_aug, b_lon_aug, LON_STATE_MAX, LON_INPUT_MAX, q_weight)
    k_lat = lqr(a_lat_aug, b_lat_aug, LAT_STATE_MAX, LAT_INPUT_MAX, q_weight)

    # 100 Hz is the fastest rate the node allows; dt is the slowest the parameters allow.
    rho_lon = max(check_discrete(a_lon_aug, b_lon_aug, k_lon, h, "longitudinal") for h in (0.01, dt_max))
    rho_lat = max(check_discrete(a_lat_aug, b_lat_aug, k_lat, h, "lateral") for h in (0.01, dt_max))
    return dict(vt=vt, alpha=alpha, de=de, dt=dt, k_lon=k_lon, k_lat=k_lat, rho_lon=rho_lon,
                rho_lat=rho_lat)


def matrix_lines(k):
    """A gain matrix as YAML rows."""
    return ["  - [" + ", ".join(num(v) for v in row) + "]" for row in k]


def gains_text(g, q_weight, airframe_sha):
    """gains.yaml: the design trim and the gains g, with what they were designed from."""
    lines = [
        "# GENERATED by drone_ros/gnc/design/design_gains.py from this folder's airframe.yaml and",
        "# controller_param.yaml. Do not edit: change the data and rerun the script. The build turns",
        "# it into the GNC's gnc_aircraft.h (tools/gen_gnc_aircraft.py).",
        "airframe_sha256: %s" % airframe_sha,
        "# controller_param.yaml's Q_weight the gains were made with: the node refuses another.",
        "design_q_weight: %s" % num(q_weight),
        "# Worst spectral radius of the sampled closed loop over 100 Hz and controller_param.yaml's dt.",
        "spectral_radius:",
        "  lon: %s" % num(g["rho_lon"]),
        "  lat: %s" % num(g["rho_lat"]),
        "# Level flight at the design airspeed.",
        "trim:",
        "  airspeed_m_s: %s" % num(g["vt"]),
        "  alpha_rad: %s" % num(g["alpha"]),
        "  theta_rad: %s" % num(g["alpha"]),
        "  elevator_rad: %s" % num(g["de"]),
        "  throttle: %s" % num(g["dt"]),
        "# u_lon = [elevator rad, throttle] = trim - k_lon * [dV m/s, dalpha rad, q rad/s, dtheta rad,",
        "#         integral(V - V_cmd) m, integral(theta - theta_cmd) rad s]",
        "k_lon:",
    ]
    lines += matrix_lines(g["k_lon"])
    lines += [
        "# u_lat = [aileron rad, rudder rad] = -k_lat * [beta rad, p rad/s, r rad/s, dphi rad,",
        "#         integral(phi - phi_cmd) rad s]",
        "k_lat:",
    ]
    lines += matrix_lines(g["k_lat"])
    return "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("aircraft_dir", help="aircraft/<name>: reads its airframe.yaml and controller_param.yaml")
    parser.add_argument("--out", help="where to write (default: AIRCRAFT_DIR/gains.yaml, the checked-in file)")
    args = parser.parse_args()

    airframe_path = os.path.join(args.aircraft_dir, "airframe.yaml")
    params_path = os.path.join(args.aircraft_dir, "controller_param.yaml")
    out = args.out or os.path.join(args.aircraft_dir, "gains.yaml")
    data = load_airframe(airframe_path)
    params = check_config.load(params_path, "controller_param")
    q_weight = float(params["Q_weight"])
    dt_max = float(params["dt"])
    af = Airframe(data)

    g = design(af, data, q_weight, dt_max)
    with open(airframe_path, "rb") as f:
        airframe_sha = hashlib.sha256(f.read()).hexdigest()

    text = gains_text(g, q_weight, airframe_sha)
    with open(out, "w", encoding="utf-8", newline="\n") as f:
        f.write(text)
    print("trim: V=%.3f m/s alpha=%.4f rad elevator=%.4f rad throttle=%.4f"
          % (g["vt"], g["alpha"], g["de"], g["dt"]))
    print("wrote %s" % out)


if __name__ == "__main__":
    main()
