"""The aircraft data the flight-dynamics model is generated from: airframe.yaml and limits.yaml.

Everything the simulator knows about an aircraft comes through here, so the JSBSim model, the
trim and the tests read one set of numbers. SI units in the attribute names.
"""
import bisect
import math
import os
from dataclasses import dataclass

import numpy as np

from stack_tools import check_config  # noqa: E402  (aircraft/schema/: no unknown, missing or mistyped key)
from stack_tools.airframe_body import AirframeBody

LBF_PER_N = 0.2248089430997105


@dataclass(frozen=True)
class Contact:
    name: str
    kind: str               # "BOGEY" (a wheel) or "STRUCTURE" (a skid, wingtip, tail)
    x_m: float              # body FRD from the CG: forward, right, down
    y_m: float
    z_m: float
    max_steer_deg: float = 0.0   # steerable wheel: full rudder turns it this far


@dataclass(frozen=True)
class ServoSpec:
    limit_deg: float        # travel, symmetric about neutral (throttle: 0..1)
    rate_per_s: float       # deg/s for surfaces, 1/s for the throttle


def _load(path):
    return check_config.load(path)  # the schema by the file's name (airframe.yaml, limits.yaml)


class Airframe(AirframeBody):
    """airframe.yaml + limits.yaml of one aircraft folder, with the derived stall figures."""

    def __init__(self, aircraft_dir):
        self.dir = os.path.abspath(aircraft_dir)
        data = _load(os.path.join(self.dir, "airframe.yaml"))
        limits = _load(os.path.join(self.dir, "limits.yaml"))
        super().__init__(data)
        self.name = str(data["aircraft"])
        sim = data["simulation"]
        stall = sim["stall"]
        self.cl_min = float(stall["cl_min"])
        self.stall_drop_deg = float(stall["lift_drop_deg"])
        self.post_stall_cl_fraction = float(stall["post_stall_cl_fraction"])
        self.flat_plate_cd90 = float(stall["flat_plate_cd90"])

        act = limits["actuators"]
        servo = sim["servo"]
        rate = float(servo["surface_rate_deg_per_s"])
        self.servos = {
            "elevator": ServoSpec(float(act["elevator_limit_deg"]), rate),
            "aileron": ServoSpec(float(act["aileron_limit_deg"]), rate),
            "rudder": ServoSpec(float(act["rudder_limit_deg"]), rate),
        }
        self.throttle_min = float(act["throttle_min"])
        self.throttle_max = float(act["throttle_max"])
        self.throttle_rate_per_s = float(servo["throttle_rate_per_s"])
        self.servo_delay_s = float(servo["transport_delay_s"])

        gear = sim["gear"]
        self.gear_spring_n_per_m = float(gear["spring_n_per_m"])
        self.gear_damping_n_s_per_m = float(gear["damping_n_s_per_m"])
        self.gear_static_friction = float(gear["static_friction"])
        self.gear_dynamic_friction = float(gear["dynamic_friction"])
        self.gear_rolling_friction = float(gear["rolling_friction"])
        self.contacts = [Contact(str(c["name"]), str(c["type"]), float(c["x_m"]), float(c["y_m"]),
                                 float(c["z_m"]), float(c.get("max_steer_deg", 0.0)))
                         for c in gear["contacts"]]
        crash = sim["crash"]
        self.crash_sink_mps = float(crash["sink_mps"])
        self.crash_roll_deg = float(crash["roll_deg"])
        self.crash_pitch_min_deg = float(crash["pitch_min_deg"])
        self.crash_pitch_max_deg = float(crash["pitch_max_deg"])
        self.stall_speed_limit_ftps = float(limits["state"]["stall_speed_ftps"])
        self._check()

    def _check(self):
        a = self.aero
        if not a["cl_max"] > a["cl0"]:
            raise ValueError(f"{self.name}: cl_max {a['cl_max']} must exceed cl0 {a['cl0']}")
        if not self.cl_min < a["cl0"]:
            raise ValueError(f"{self.name}: cl_min {self.cl_min} must be below cl0 {a['cl0']}")
        if not 0.0 < self.post_stall_cl_fraction < 1.0:
            raise ValueError(f"{self.name}: post_stall_cl_fraction must be in (0, 1)")
        if not any(c.kind == "BOGEY" for c in self.contacts):
            raise ValueError(f"{self.name}: the gear needs at least one wheel (type BOGEY)")

    # Stall: lift is linear in alpha up to alpha_stall, where it reaches cl_max.
    @property
    def alpha_stall_rad(self):
        return (self.aero["cl_max"] - self.aero["cl0"]) / self.aero["cl_alpha_per_rad"]

    @property
    def alpha_stall_neg_rad(self):
        return (self.cl_min - self.aero["cl0"]) / self.aero["cl_alpha_per_rad"]

    def lift_table(self):
        """(alpha_deg, CL) breakpoints of the static lift curve over -180..180 deg.

        Linear between the negative and positive stall, falls by (1 - post_stall_cl_fraction)
        within lift_drop_deg past each stall, then blends into a flat plate (CN = cd90 sin(alpha))
        by 40 deg, which it follows to +-180 deg."""
        a = self.aero
        cl0 = a["cl0"]
        cd90 = self.flat_plate_cd90
        a_s = math.degrees(self.alpha_stall_rad)
        a_n = math.degrees(self.alpha_stall_neg_rad)
        drop = self.stall_drop_deg
        frac = self.post_stall_cl_fraction

        def plate(deg):
            r = math.radians(deg)
            return cd90 * math.sin(r) * math.cos(r)

        blend_deg = 40.0
        if not a_s + drop < blend_deg or not a_n - drop > -blend_deg:
            raise ValueError(f"{self.name}: stall angles too large for the post-stall model")
        pts = []
        for deg in range(-180, -int(blend_deg) + 1, 5):
            pts.append((float(deg), plate(deg)))
        pts.append((a_n - drop, frac * self.cl_min))
        pts.append((a_n, self.cl_min))
        pts.append((a_s, a["cl_max"]))
        pts.append((a_s + drop, frac * a["cl_max"]))
        for deg in range(int(blend_deg), 181, 5):
            pts.append((float(deg), plate(deg)))
        # Passing through (0, cl0) keeps the linear range exact at the breakpoints too.
        pts.append((0.0, cl0))
        pts.sort()
        return pts

    # Roll damping by strip theory. A rolling wing meets alpha + p y / V at span station y, so the
    # rolling moment of p is the span integral of the lift curve's change times y. In attached
    # flow that is cl_p p b/2V; past the stall the down-going wing loses lift (autorotation, the
    # wing drop), but only until its tip has crossed the lift break: beyond that the integral
    # grows with p again. A linear cl_p times the local slope would keep autorotation accelerating
    # at any rate (snap rolls of 1,000 deg/s on a 4.5 m wing); the integral bounds it.
    ROLL_RATE_PHAT = (0.0, 0.005, 0.01, 0.02, 0.035, 0.05, 0.075, 0.1, 0.15, 0.2, 0.3, 0.5, 0.8, 1.2, 2.0)
    STRIPS = 200

    def roll_damping_phat(self, alpha_deg, phat):
        """The roll rate that, times cl_p, gives the rolling moment coefficient of roll rate phat
        (= p b / 2V) at alpha_deg: phat itself in attached flow; (3 / 2 cl_alpha) times the span
        integral of (CL(alpha + phat eta) - CL(alpha)) eta over eta = 2y/b in [-1, 1], which is
        phat where CL is linear (rectangular strips; cl_p carries the planform)."""
        lift = self.lift_table()
        xs = [x for x, _ in lift]

        def cl(deg):
            deg = (deg + 180.0) % 360.0 - 180.0
            i = min(max(bisect.bisect_right(xs, deg), 1), len(xs) - 1)
            (x0, y0), (x1, y1) = lift[i - 1], lift[i]
            return y0 + (y1 - y0) * (deg - x0) / (x1 - x0)

        base, n = cl(alpha_deg), self.STRIPS
        total = 0.0
        for k in range(n):
            eta = -1.0 + (k + 0.5) * 2.0 / n
            total += (cl(alpha_deg + math.degrees(phat * eta)) - base) * eta * (2.0 / n)
        return 1.5 * total / self.aero["cl_alpha_per_rad"]

    def roll_damping_grid(self):
        """(alphas_deg, phats, rows): roll_damping_phat on a grid fine around the stalls, odd in
        phat; JSBSim interpolates in it and holds the edges."""
        alphas = sorted(set([float(d) for d in range(-180, -40, 10)] + [float(d) for d in range(-40, 41)]
                            + [float(d) for d in range(50, 181, 10)]))
        phats = sorted(set([-x for x in self.ROLL_RATE_PHAT] + list(self.ROLL_RATE_PHAT)))
        # roll_damping_phat's arithmetic, operation for operation, on every cell at once (numpy's
        # elementwise float64 operations round as Python's, and each cell still sums its strips
        # in order): the same bits, where the cell-by-cell loop cost every flight 2.6 s of model
        # set-up (8.8 s on the loaded CI machine).
        lift = self.lift_table()
        xs = np.array([x for x, _ in lift])
        ys = np.array([y for _, y in lift])

        def cl(deg):
            deg = (deg + 180.0) % 360.0 - 180.0
            i = np.clip(np.searchsorted(xs, deg, side="right"), 1, len(xs) - 1)
            x0, y0, x1, y1 = xs[i - 1], ys[i - 1], xs[i], ys[i]
            return y0 + (y1 - y0) * (deg - x0) / (x1 - x0)

        alpha, phat = np.meshgrid(np.array(alphas), np.array(phats), indexing="ij")
        base, n = cl(alpha), self.STRIPS
        total = np.zeros_like(alpha)
        for k in range(n):
            eta = -1.0 + (k + 0.5) * 2.0 / n
            total += (cl(alpha + np.degrees(phat * eta)) - base) * eta * (2.0 / n)
        rows = (1.5 * total / self.aero["cl_alpha_per_rad"]).tolist()
        return alphas, phats, rows

    def separation_drag_table(self):
        """(alpha_deg, CD_sep): zero in attached flow, rising to flat-plate drag past the stall."""
        cd90 = self.flat_plate_cd90
        a_s = math.degrees(self.alpha_stall_rad)
        a_n = math.degrees(self.alpha_stall_neg_rad)
        drop = self.stall_drop_deg
        pts = [(a_n, 0.0), (a_s, 0.0)]
        for deg in range(-180, 181, 5):
            if deg >= a_s + drop or deg <= a_n - drop:
                pts.append((float(deg), cd90 * math.sin(math.radians(deg)) ** 2))
        pts.append((a_s + drop, cd90 * math.sin(math.radians(a_s + drop)) ** 2))
        pts.append((a_n - drop, cd90 * math.sin(math.radians(a_n - drop)) ** 2))
        pts = sorted(set(pts))
        return pts

    def cl_static(self, alpha_rad):
        """The static lift curve as the generated JSBSim table interpolates it."""
        xs, ys = zip(*self.lift_table())
        return float(np.interp(math.degrees(alpha_rad), xs, ys))

    def cd_separation(self, alpha_rad):
        xs, ys = zip(*self.separation_drag_table())
        return float(np.interp(math.degrees(alpha_rad), xs, ys))

    def one_g_stall_speed_mps(self, rho_kg_m3, g_m_s2):
        """1 g stall speed at cl_max (elevator lift ignored): V = sqrt(2 m g / (rho S cl_max))."""
        return math.sqrt(2.0 * self.mass_kg * g_m_s2 / (rho_kg_m3 * self.wing_area_m2 * self.aero["cl_max"]))
