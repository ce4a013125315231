"""Every folder of aircraft/ is an aircraft the stack can be built for: its gains are the design's
own (a rerun reproduces gains.yaml byte for byte), its sampled inner loops are stable, its limits
agree with its airframe (the HA generator's stall and elevator checks), and its design wind is one
the airframe can fly. Parametrised over the folders, so a new aircraft is tested by being added."""
import functools
import json
import math
import os
import subprocess
import sys

import pytest
import yaml

from stack_tools.paths import ROOT

DESIGN = os.path.join(ROOT, "drone_ros", "gnc", "design")
# The closed loops' poles per axis, computed where the design's modules are (the design is a
# script folder, not a package: run from it, as test_config_schemas does). One linearisation about
# the design trim (design_gains.loop_models: each axis with its error integrals, +phi, +V, +theta)
# closed twice: by the LQR gains of gains.yaml ("lqr") and by the HA's safety controller with
# limits.yaml's gains ("ha", ha_safety_ctrl.c's loops: aileron = kp (phi_cmd - phi) - kd p + ki
# int(phi_cmd - phi), rudder = yaw damper x r, nose-up elevator likewise on theta and q, throttle
# = kp (V_cmd - V) + ki int; degrees for degrees, so radians serve as well).
POLES = """
import sys, json
import numpy as np, yaml
import design_gains
from airframe_model import Airframe, FT_PER_M, load_airframe
folder = sys.argv[1]
af = Airframe(load_airframe(folder + "/airframe.yaml"))
gains = yaml.safe_load(open(folder + "/gains.yaml"))
g = yaml.safe_load(open(folder + "/limits.yaml"))["safety_controller"]
t = gains["trim"]
x0 = np.array([t["airspeed_m_s"], t["alpha_rad"], 0, 0, 0, 0, 0, t["theta_rad"]], dtype=float)
a, b = design_gains.jacobians(af, x0, [t["elevator_rad"], 0.0, 0.0, t["throttle"]])
(a_lon, b_lon), (a_lat, b_lat) = design_gains.loop_models(a, b)
# u = -k x: lon x = [V, alpha, q, theta, int V, int theta], u = [elevator (TE down), throttle];
# lat x = [beta, p, r, phi, int phi], u = [aileron, rudder (TE left: yaw left against a yaw right)].
ha_lon = np.zeros((2, 6))
ha_lon[0, 3], ha_lon[0, 2], ha_lon[0, 5] = -g["pitch_kp"], -g["pitch_kd"], -g["pitch_ki"]
ha_lon[1, 0], ha_lon[1, 4] = g["throttle_kp_per_ftps"] * FT_PER_M, g["throttle_ki_per_ft"] * FT_PER_M
ha_lat = np.zeros((2, 5))
ha_lat[0, 3], ha_lat[0, 1], ha_lat[0, 4] = g["roll_kp"], g["roll_kd"], g["roll_ki"]
ha_lat[1, 2] = -g["yaw_damper_gain"]
out = {}
for law, k_lon, k_lat in (("lqr", gains["k_lon"], gains["k_lat"]), ("ha", ha_lon, ha_lat)):
    out[law] = {}
    for axis, aa, bb, k in (("lon", a_lon, b_lon, k_lon), ("lat", a_lat, b_lat, k_lat)):
        poles = np.linalg.eigvals(aa - bb @ np.array(k))
        out[law][axis] = [[p.real, p.imag] for p in poles]
print(json.dumps(out))
"""


@functools.lru_cache(maxsize=None)
def closed_loop_poles(name):
    done = subprocess.run([sys.executable, "-c", POLES, folder(name)], cwd=DESIGN,
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


AIRCRAFT = sorted(name for name in os.listdir(os.path.join(ROOT, "aircraft"))
                  if os.path.isfile(os.path.join(ROOT, "aircraft", name, "limits.yaml")))


def folder(name):
    return os.path.join(ROOT, "aircraft", name)


def test_there_is_more_than_one_aircraft():
    assert {"DG808", "Aerosonde"} <= set(AIRCRAFT)


@pytest.mark.parametrize("name", AIRCRAFT)
def test_rerunning_the_design_reproduces_the_checked_in_gains(name, tmp_path):
    out = tmp_path / "gains.yaml"
    done = subprocess.run([sys.executable, os.path.join(DESIGN, "design_gains.py"), folder(name),
                           "--out", str(out)], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    with open(os.path.join(folder(name), "gains.yaml"), encoding="utf-8") as f:
        assert out.read_text() == f.read(), (
            "aircraft/%s's data or the design changed: rerun design_gains.py aircraft/%s" % (name, name))


@pytest.mark.parametrize("name", AIRCRAFT)
def test_the_inner_loops_are_stable_about_the_design_trim(name):
    """The closed loop of the linearised airframe with the checked-in gains: every pole in the
    left half plane, in both axes (the integrators included)."""
    for axis, poles in closed_loop_poles(name)["lqr"].items():
        assert max(re for re, _im in poles) < -0.01, "%s %s poles: %s" % (name, axis, poles)


@pytest.mark.parametrize("name", AIRCRAFT)
def test_the_design_trims_inside_the_aircrafts_limits(name):
    with open(os.path.join(folder(name), "gains.yaml"), encoding="utf-8") as f:
        trim = yaml.safe_load(f)["trim"]
    with open(os.path.join(folder(name), "limits.yaml"), encoding="utf-8") as f:
        limits = yaml.safe_load(f)
    act, state = limits["actuators"], limits["state"]
    assert abs(math.degrees(trim["elevator_rad"])) < act["elevator_limit_deg"]
    assert act["throttle_min"] < trim["throttle"] < act["throttle_max"]
    assert math.degrees(trim["alpha_rad"]) < state["stall_alpha_deg"]
    assert trim["airspeed_m_s"] / 0.3048 > state["stall_speed_ftps"] * state["handback_stall_multiple"]


@pytest.mark.parametrize("name", AIRCRAFT)
def test_the_limits_agree_with_the_airframe(name, tmp_path):
    """The HA's generator refuses a stall speed, stall angle or elevator stop its airframe
    contradicts; each aircraft's limits pass it."""
    done = subprocess.run([sys.executable, os.path.join(ROOT, "tools", "gen_aircraft_config.py"),
                           os.path.join(folder(name), "limits.yaml"), str(tmp_path / "config.h")],
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    assert '.aircraft = "%s"' % name in (tmp_path / "config.h").read_text()


@pytest.mark.parametrize("name", AIRCRAFT)
def test_the_design_wind_is_one_the_airframe_flies(name):
    from hil.design_wind import DesignWind
    with open(os.path.join(folder(name), "limits.yaml"), encoding="utf-8") as f:
        limits = yaml.safe_load(f)
    with open(os.path.join(folder(name), "airframe.yaml"), encoding="utf-8") as f:
        airframe = yaml.safe_load(f)
    DesignWind.load(limits, airframe)  # raises with the reason when it cannot


@pytest.mark.parametrize("name", AIRCRAFT)
def test_the_roll_rate_bound_is_the_wings_own(name):
    """S_x bounds the roll rate on a row of its own (limits.yaml's roll_rate_limit_deg_per_s; pitch
    and yaw on body_rate_limit_deg_per_s), and that bound is judged by the wing it sweeps: p b / 2V
    at the design airspeed, the tips' change of angle of attack, is at most 0.3 (17 deg: past any
    small wing's stall)."""
    from stack_tools import gen_aircraft_config
    with open(os.path.join(folder(name), "limits.yaml"), encoding="utf-8") as f:
        limits = yaml.safe_load(f)
    with open(os.path.join(folder(name), "airframe.yaml"), encoding="utf-8") as f:
        airframe = yaml.safe_load(f)
    state = limits["state"]
    c = gen_aircraft_config.build(limits, airframe)
    p, q, r = (gen_aircraft_config.X_NAMES.index(k) for k in ("p_deg_s", "q_deg_s", "r_deg_s"))
    rows = c["sx"]
    assert max(row[p] for row in rows) == pytest.approx(1.0 / state["roll_rate_limit_deg_per_s"])
    for k in (q, r):
        assert max(row[k] for row in rows) == pytest.approx(1.0 / state["body_rate_limit_deg_per_s"])
    v_m_s = airframe["design_point"]["airspeed_ftps"] / gen_aircraft_config.FT_PER_M
    span_m = airframe["geometry"]["wing_span_m"]
    pb_2v = math.radians(state["roll_rate_limit_deg_per_s"]) * span_m / (2 * v_m_s)
    assert pb_2v <= 0.3, "%s: p b / 2V %.2f at %.1f m/s" % (name, pb_2v, v_m_s)


@pytest.mark.parametrize("name", AIRCRAFT)
def test_the_has_safety_controller_is_stable_and_damped_on_the_airframe(name):
    """The HA's own loops, with the aircraft's limits.yaml gains, on its linearised airframe:
    every pole in the left half plane and every oscillation damped at least 0.4 (the DG808's short
    period 0.47, its roll and dutch roll 0.44). The DG808's gains on the Aerosonde, whose pitch
    damping is a quarter of the DG808's (cm_q -3.6 against -14), left its short period at 0.29."""
    for axis, poles in closed_loop_poles(name)["ha"].items():
        for re, im in poles:
            zeta = -re / math.hypot(re, im)
            assert re < -0.01 and (abs(im) < 1e-9 or zeta >= 0.4), (
                "%s %s: pole %.2f%+.2fj (damping %.2f): %s" % (name, axis, re, im, zeta, poles))
