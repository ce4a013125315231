"""The HiL flight-dynamics model: JSBSim, driven step by step from Python.

One Fdm is one aircraft in one atmosphere. The JSBSim model is generated from the aircraft
folder (model_xml.py), the servos (servo.py) and the turbulence (turbulence.py) run here, in
lockstep with JSBSim's integrator, so everything is decided by the seed and the commands."""
import math
import os
import tempfile

import jsbsim
import numpy as np

from stack_common.units import FT_PER_M, M_PER_FT

from .airframe import Airframe
from .model_xml import SURFACE_PROPERTIES, THROTTLE_PROPERTY, write_model
from .servo import Servo
from .turbulence import Turbulence
from .types import Surfaces, Truth, Wind

PA_PER_PSF = 47.88025898
KG_M3_PER_SLUG_FT3 = 515.3788184
# A constant earth field for the magnetometer, NED [gauss]: roughly the mid-latitude northern
# hemisphere field (WMM: horizontal ~0.2 G, downward ~0.45 G). Not site-specific on purpose.
DEFAULT_MAG_FIELD_NED_GAUSS = (0.2, 0.0, 0.45)
_SETTLE_S = 3.0          # parked start: time on the springs before the state is frozen as the IC
# Parked, the glider is held as a crew holds it in a wind (a hand on the wing tip, one on the
# tail): tipped this far from where it settled, it is put back at rest there. Unheld, a tailwind
# past the aircraft's limit (HiL campaign: 9.8 to 10.9 m/s) lifted the tail and crashed it in
# 0.6 s, before any launch.
_HOLD_DEG = 3.0

jsbsim.FGJSBBase().debug_lvl = 0   # no banner or model echo on stdout


class TrimError(ValueError):
    """No trimmed level flight at the requested state (too slow, too fast, beyond a limit)."""


class FdmCrash(RuntimeError):
    """The aircraft hit the ground beyond the airframe's crash limits (or the state diverged).
    The flight is over: advance() raises again until the next reset; truth() keeps returning
    the state at the crash, with crashed True."""


def _check_finite(**values):
    for name, v in values.items():
        if not math.isfinite(float(v)):
            raise ValueError(f"{name} must be finite, not {v}")


class Fdm:
    """One simulated aircraft (hil/HIL_INTERFACES.md section 1).

    Fdm(aircraft_dir, seed, dt_s, wind, work_dir): generates the JSBSim model from
    aircraft_dir/airframe.yaml and limits.yaml into work_dir (a temporary folder, removed on
    close(), by default). Then reset_airborne() or reset_on_ground(), and in a loop
    set_surfaces(), advance() and truth(). The seed drives the turbulence only; a reset starts
    it over, so every reset with the same commands replays the same flight bit for bit."""

    def __init__(self, aircraft_dir, seed, dt_s=1.0 / 200.0, wind=None, work_dir=None,
                 mag_field_ned_gauss=DEFAULT_MAG_FIELD_NED_GAUSS, temperature_deviation_c=0.0):
        if not dt_s > 0.0:
            raise ValueError(f"dt_s must be positive, not {dt_s}")
        _check_finite(temperature_deviation_c=temperature_deviation_c)
        # The day's temperature against ISA at every height (JSBSim's atmosphere/delta-T): a hot
        # day thins the air at the same pressure, so the same true airspeed reads lower on a pitot.
        self.temperature_deviation_c = float(temperature_deviation_c)
        self.airframe = Airframe(aircraft_dir)
        self.seed = int(seed)
        self.dt_s = float(dt_s)
        self.wind = wind if wind is not None else Wind()
        if not isinstance(self.wind, Wind):
            raise TypeError("wind must be a hil.fdm.Wind")
        self.mag_field_ned_gauss = tuple(float(x) for x in mag_field_ned_gauss)
        self._tmp = None
        if work_dir is None:
            self._tmp = tempfile.TemporaryDirectory(prefix="hil_fdm_")
            work_dir = self._tmp.name
        self.work_dir = os.path.abspath(work_dir)
        self.model_path = write_model(self.airframe, self.work_dir)

        af = self.airframe
        delay_steps = int(round(af.servo_delay_s / self.dt_s))
        self._servos = [Servo(-af.servos[k].limit_deg, af.servos[k].limit_deg, af.servos[k].rate_per_s,
                              delay_steps, self.dt_s) for k in ("elevator", "aileron", "rudder")]
        self._servos.append(Servo(af.throttle_min, af.throttle_max, af.throttle_rate_per_s,
                                  delay_steps, self.dt_s))
        self._exec = None
        self._held = None  # parked: (put it back, roll, pitch where it settled), else None
        self._steps = 0
        self._turbulence = None
        self._crash = None
        self._crash_truth = None

    # --- lifetime -------------------------------------------------------------------------
    def close(self):
        self._exec = None
        if self._tmp is not None:
            self._tmp.cleanup()
            self._tmp = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    # --- set-up ---------------------------------------------------------------------------
    def _new_exec(self):
        ex = jsbsim.FGFDMExec(self.work_dir)
        ex.set_debug_level(0)
        if not ex.load_model(self.airframe.name):
            raise RuntimeError(f"JSBSim could not load {self.model_path}")
        ex.set_dt(self.dt_s)
        ex["atmosphere/delta-T"] = self.temperature_deviation_c * 1.8  # Rankine
        pm = ex.get_property_manager()

        def node(path):
            n = pm.get_node(path)
            if n is None:
                raise RuntimeError(f"JSBSim model has no property {path}")
            return n

        self._exec = ex
        self._n_surface = [node(SURFACE_PROPERTIES[k]) for k in ("elevator", "aileron", "rudder")]
        self._n_throttle = node(THROTTLE_PROPERTY)
        self._n_wind = [node("atmosphere/wind-north-fps"), node("atmosphere/wind-east-fps"),
                        node("atmosphere/wind-down-fps")]
        names = ["position/lat-geod-deg", "position/long-gc-deg", "position/geod-alt-ft", "position/h-agl-ft",
                 "position/terrain-elevation-asl-ft", "velocities/v-north-fps", "velocities/v-east-fps",
                 "velocities/v-down-fps", "attitude/phi-rad", "attitude/theta-rad", "attitude/psi-rad",
                 "velocities/p-rad_sec", "velocities/q-rad_sec", "velocities/r-rad_sec",
                 "forces/fbx-total-lbs", "forces/fby-total-lbs", "forces/fbz-total-lbs",
                 "velocities/vtrue-fps", "velocities/vc-fps", "aero/alpha-deg", "aero/beta-deg",
                 "gear/wow", "atmosphere/P-psf", "atmosphere/T-R", "inertia/mass-slugs",
                 "atmosphere/rho-slugs_ft3"]
        self._n_truth = [node(n) for n in names]
        self._n_psi = node("attitude/psi-rad")
        self._n_vt = node("velocities/vtrue-fps")
        self._n_agl = node("position/h-agl-ft")
        self._n_gear_fz = node("forces/fbz-gear-lbs")
        self._n_crash = [node(n) for n in ("velocities/v-down-fps", "attitude/phi-deg", "attitude/theta-deg",
                                           "position/h-agl-ft")]
        return ex

    def _mean_wind_ned_fps(self):
        from_rad = math.radians(self.wind.mean_from_deg)
        m = self.wind.mean_mps * FT_PER_M
        return -m * math.cos(from_rad), -m * math.sin(from_rad), 0.0

    def _set_ic_common(self, ex, lat_deg, lon_deg, ground_msl_m, height_agl_m, heading_deg, wind):
        ex["ic/lat-geod-deg"] = float(lat_deg)
        ex["ic/long-gc-deg"] = float(lon_deg)
        ex["ic/terrain-elevation-ft"] = float(ground_msl_m) * FT_PER_M
        ex["ic/h-agl-ft"] = float(height_agl_m) * FT_PER_M
        ex["ic/psi-true-deg"] = float(heading_deg) % 360.0
        if wind:
            wn, we, _ = self._mean_wind_ned_fps()
            ex["ic/vw-mag-fps"] = math.hypot(wn, we)
            # JSBSim's ic/vw-dir-deg is where the wind blows to, not where it comes from.
            ex["ic/vw-dir-deg"] = (float(self.wind.mean_from_deg) + 180.0) % 360.0
        else:
            ex["ic/vw-mag-fps"] = 0.0

    def _init_state(self, ex, ground_vel_ned_fps, theta_rad, phi_rad):
        """Attitude and ground velocity given, body rates zero; JSBSim's IC in the mean wind.
        (Given this way JSBSim's IC keeps the wind out of the heading, which its airspeed
        setters do not.)"""
        ex["ic/theta-rad"] = theta_rad
        ex["ic/phi-rad"] = phi_rad
        ex["ic/vn-fps"], ex["ic/ve-fps"], ex["ic/vd-fps"] = ground_vel_ned_fps
        ex["ic/p-rad_sec"] = 0.0
        ex["ic/q-rad_sec"] = 0.0
        ex["ic/r-rad_sec"] = 0.0
        if not ex.run_ic():
            raise RuntimeError("JSBSim run_ic failed")

    def _apply_servos(self, positions):
        for n, p in zip(self._n_surface, positions[:3]):
            n.set_double_value(math.radians(p))
        self._n_throttle.set_double_value(positions[3])

    def _start(self, positions):
        """Servos at rest at positions, time zero, turbulence from the seed's start."""
        for s, p in zip(self._servos, positions):
            s.reset(p)
        self._apply_servos([s.position for s in self._servos])
        self._steps = 0
        self._crash = None
        self._crash_truth = None
        self._turbulence = Turbulence(self.wind.turbulence, self.seed, self.dt_s)
        self._wind_mean = self._mean_wind_ned_fps()
        self._set_wind(self._gust())

    def set_wind(self, wind):
        """A new wind from now on, in flight (a wind shift, a gust front, a shear): the mean wind
        at once, the turbulence at the new level from its present state (the Dryden state is
        kept in units of its intensity, so the gusts carry on, scaled). Deterministic: the same
        calls at the same steps give the same flight."""
        if not isinstance(wind, Wind):
            raise TypeError("wind must be a hil.fdm.Wind")
        self.wind = wind
        if self._exec is None:
            return
        self._wind_mean = self._mean_wind_ned_fps()
        self._turbulence.set_level(wind.turbulence)
        self._set_wind(self._gust_now if wind.turbulence != "none" else (0.0, 0.0, 0.0))

    def _gust(self):
        agl_m = self._n_agl.get_double_value() * M_PER_FT
        vt_mps = self._n_vt.get_double_value() * M_PER_FT
        return self._turbulence.step(agl_m, vt_mps, self._n_psi.get_double_value())

    def _set_wind(self, gust_ned_mps):
        self._gust_now = gust_ned_mps
        for n, mean, g in zip(self._n_wind, self._wind_mean, gust_ned_mps):
            n.set_double_value(mean + g * FT_PER_M)

    def _trim_residual(self, ex, base_ic, vt_fps, x):
        alpha, de, thr = x
        base_ic()
        ex["ic/vt-fps"] = vt_fps
        ex["ic/beta-rad"] = 0.0
        ex["ic/phi-rad"] = 0.0
        ex["ic/gamma-rad"] = 0.0
        ex["ic/alpha-rad"] = alpha
        ex["ic/p-rad_sec"] = 0.0
        ex["ic/q-rad_sec"] = 0.0
        ex["ic/r-rad_sec"] = 0.0
        self._apply_servos([math.degrees(de), 0.0, 0.0, thr])
        if not ex.run_ic():
            raise RuntimeError("JSBSim run_ic failed")
        # qdot weighted up: per unit of trim error it is about ten times smaller than udot, wdot.
        return np.array([ex["accelerations/udot-ft_sec2"], ex["accelerations/wdot-ft_sec2"],
                         ex["accelerations/qdot-rad_sec2"] * 10.0])

    def reset_airborne(self, lat_deg, lon_deg, ground_msl_m, height_agl_m, heading_deg, airspeed_mps):
        """Trimmed wings-level, level flight at that state; returns the trim Surfaces.
        Raises TrimError (and leaves the Fdm unset) when there is no such trim."""
        _check_finite(lat_deg=lat_deg, lon_deg=lon_deg, ground_msl_m=ground_msl_m,
                      height_agl_m=height_agl_m, heading_deg=heading_deg, airspeed_mps=airspeed_mps)
        try:
            return self._reset_airborne(lat_deg, lon_deg, ground_msl_m, height_agl_m, heading_deg,
                                        airspeed_mps)
        except Exception:
            self._exec = None
            raise

    def _reset_airborne(self, lat_deg, lon_deg, ground_msl_m, height_agl_m, heading_deg, airspeed_mps):
        self._held = None  # launched: nobody holds it any more
        af = self.airframe
        clearance_m = max(c.z_m for c in af.contacts)
        if not height_agl_m > clearance_m:
            raise ValueError(f"height_agl_m {height_agl_m} puts the gear on the ground: an airborne start "
                             f"needs more than {clearance_m} m (reset_on_ground parks it)")
        ex = self._new_exec()

        # A steady uniform wind does not change the air-relative trim: trim in still air, then
        # start in the wind with the same air-relative state.
        def base_ic():
            self._set_ic_common(ex, lat_deg, lon_deg, ground_msl_m, height_agl_m, heading_deg, wind=False)

        vt_fps = float(airspeed_mps) * FT_PER_M
        a = af.aero
        # Start from the linear model's trim (lift = weight, Cm = 0); Newton on JSBSim's own
        # accelerations does the rest (density, gravity and the earth's rotation where it flies).
        cl_req = (2.0 * af.mass_kg * af.design_gravity_m_s2
                  / (af.design_air_density_kg_m3 * af.wing_area_m2 * float(airspeed_mps) ** 2))
        if cl_req > a["cl_max"]:
            raise TrimError(f"{airspeed_mps} m/s is below the stall speed: level flight needs CL "
                            f"{cl_req:.2f} > cl_max {a['cl_max']}")
        alpha0 = (cl_req - a["cl0"]) / a["cl_alpha_per_rad"]
        de0 = -(a["cm0"] + a["cm_alpha_per_rad"] * alpha0) / a["cm_elevator_per_rad"]
        x = np.array([alpha0, de0, 0.3])
        steps = np.array([1e-5, 1e-5, 1e-4])
        r = self._trim_residual(ex, base_ic, vt_fps, x)
        for _ in range(30):
            if np.max(np.abs(r)) < 1e-7:
                break
            jac = np.empty((3, 3))
            for j in range(3):
                xp = x.copy()
                xp[j] += steps[j]
                jac[:, j] = (self._trim_residual(ex, base_ic, vt_fps, xp) - r) / steps[j]
            dx = np.linalg.solve(jac, -r)
            x = x + dx
            r = self._trim_residual(ex, base_ic, vt_fps, x)
        alpha, de, thr = x
        if not np.max(np.abs(r)) < 1e-5:
            raise TrimError(f"no level trim at {airspeed_mps} m/s (residual {r.tolist()})")
        if not af.alpha_stall_neg_rad < alpha < af.alpha_stall_rad:
            raise TrimError(f"{airspeed_mps} m/s is below the stall: "
                            f"trim alpha {math.degrees(alpha):.1f} deg")
        if not af.throttle_min <= thr <= af.throttle_max:
            raise TrimError(f"level flight at {airspeed_mps} m/s needs throttle {thr:.3f}, "
                            f"outside [{af.throttle_min}, {af.throttle_max}]")
        if not abs(math.degrees(de)) <= af.servos["elevator"].limit_deg:
            raise TrimError(f"level flight at {airspeed_mps} m/s needs elevator {math.degrees(de):.1f} deg")
        trim = Surfaces(math.degrees(de), 0.0, 0.0, float(thr))
        ex = self._new_exec()
        self._set_ic_common(ex, lat_deg, lon_deg, ground_msl_m, height_agl_m, heading_deg, wind=True)
        psi = math.radians(heading_deg)
        wn, we, wd = self._mean_wind_ned_fps()
        self._apply_servos([trim.elevator_deg, 0.0, 0.0, trim.throttle])
        air_ned = (vt_fps * math.cos(psi), vt_fps * math.sin(psi), 0.0)
        self._init_state(ex, tuple(a + w for a, w in zip(air_ned, (wn, we, wd))), alpha, 0.0)
        self._start([trim.elevator_deg, 0.0, 0.0, trim.throttle])
        # Launched in the air where it starts: the turbulence's gust there (drawn stationary by
        # _start) joins the mean wind in the start's ground velocity, so the first period flies at
        # the trim airspeed and angle of attack. In the mean wind alone, the gust at the start
        # point was a step of up to 16 ft/s on the airspeed and 13 deg on alpha (moderate
        # turbulence), the launch's doing, which the HA then had to fly out of.
        if any(self._gust_now):
            gust = tuple(g * FT_PER_M for g in self._gust_now)
            self._init_state(ex, tuple(a + w + g for a, w, g in zip(air_ned, (wn, we, wd), gust)), alpha, 0.0)
            self._set_wind(self._gust_now)
            # JSBSim's initial condition knows the mean wind only: its models run once without
            # integrating (time stays at zero) for the start's airspeed and alpha in that air.
            ex.suspend_integration()
            ex.run()
            ex.resume_integration()
        return trim

    def reset_on_ground(self, lat_deg, lon_deg, ground_msl_m, heading_deg, held=False):
        """Parked on its gear, at rest, throttle zero, surfaces neutral. held: a crew holds it until
        the next reset (tipped _HOLD_DEG from where it settled, it is put back at rest there), as
        the HiL's parked glider waiting for its airborne start; unheld, it rolls, steers and takes
        off. Held or not, it is held within _HOLD_DEG while it settles, before t = 0. RuntimeError
        when it still did not come to rest."""
        _check_finite(lat_deg=lat_deg, lon_deg=lon_deg, ground_msl_m=ground_msl_m, heading_deg=heading_deg)
        af = self.airframe
        wheel_z = max(c.z_m for c in af.contacts if c.kind == "BOGEY")
        ex = self._new_exec()

        def ground_ic(height_m, theta_rad, phi_rad):
            self._set_ic_common(ex, lat_deg, lon_deg, ground_msl_m, height_m, heading_deg, wind=True)
            self._init_state(ex, (0.0, 0.0, 0.0), theta_rad, phi_rad)

        # Wheels touching, then let the springs take the weight, and start from where it came
        # to rest (velocities zeroed) so t = 0 is already settled. A crew holds it while it
        # settles too: left alone crosswind in a strong gust, a glider's wing lifts and it rolls
        # on its back (seed 721717211 in 9.2 m/s of moderate turbulence, heading 82 deg into a
        # wind from 347 deg: inverted within 2 s, then JSBSim's state was NaN, the flight's truth
        # too, and the simulator stopped on it).
        ground_ic(wheel_z, 0.0, 0.0)
        self._start([0.0, 0.0, 0.0, 0.0])
        self._held = (lambda: ground_ic(wheel_z, 0.0, 0.0), 0.0, 0.0)
        for _ in range(int(round(_SETTLE_S / self.dt_s))):
            ex.run()
            self._hold()
        settled = (ex["position/h-agl-ft"] * M_PER_FT, ex["attitude/theta-rad"], ex["attitude/phi-rad"])
        if not all(math.isfinite(v) for v in settled):
            self._exec = None
            raise RuntimeError("the parked aircraft did not come to rest on its gear (non-finite state "
                               "after %g s of settling)" % _SETTLE_S)
        ground_ic(*settled)
        self._start([0.0, 0.0, 0.0, 0.0])
        self._held = None
        if held:
            self._held = (lambda: ground_ic(*settled), math.degrees(settled[2]), math.degrees(settled[1]))

    # --- running --------------------------------------------------------------------------
    def set_surfaces(self, surfaces):
        """Commands to the servos (msg/pwm.msg signs), clipped to their travel."""
        cmds = (surfaces.elevator_deg, surfaces.aileron_deg, surfaces.rudder_deg, surfaces.throttle)
        for c in cmds:
            if not math.isfinite(c):
                raise ValueError(f"servo command must be finite: {surfaces}")
        for s, c in zip(self._servos, cmds):
            s.set_command(c)

    def advance(self, duration_s):
        """Integrates duration_s, a whole number of dt steps."""
        if self._exec is None:
            raise RuntimeError("call reset_airborne or reset_on_ground first")
        if self._crash is not None:
            raise FdmCrash(self._crash)
        n = int(round(duration_s / self.dt_s))
        if n < 0 or abs(n * self.dt_s - duration_s) > 1e-9:
            raise ValueError(f"duration {duration_s} s is not a whole number of {self.dt_s} s steps")
        ex = self._exec
        servos = self._servos
        turbulent = self.wind.turbulence != "none"
        for _ in range(n):
            self._apply_servos([s.step() for s in servos])
            if turbulent:
                self._set_wind(self._gust())
            if not ex.run():
                raise RuntimeError("JSBSim stopped")
            if self._held is not None:
                self._hold()
            self._steps += 1
            # Anything touching the ground (or a NaN, which compares unequal too): check it.
            if self._n_gear_fz.get_double_value() != 0.0:
                self._check_crash()

    def _hold(self):
        put_back, roll0_deg, pitch0_deg = self._held
        _, roll, pitch, _ = (n.get_double_value() for n in self._n_crash)
        if abs(roll - roll0_deg) > _HOLD_DEG or abs(pitch - pitch0_deg) > _HOLD_DEG:
            put_back()

    def _check_crash(self):
        af = self.airframe
        vd_fps, roll, pitch, agl_ft = (n.get_double_value() for n in self._n_crash)
        vd = vd_fps * M_PER_FT
        if not all(math.isfinite(x) for x in (vd, roll, pitch, agl_ft)):
            reason = "the simulation diverged (non-finite state)"
        elif vd > af.crash_sink_mps:
            reason = f"hit the ground sinking at {vd:.1f} m/s (limit {af.crash_sink_mps})"
        elif abs(roll) > af.crash_roll_deg:
            reason = f"a wing dug in: bank {roll:.0f} deg on the ground (limit {af.crash_roll_deg})"
        elif not af.crash_pitch_min_deg <= pitch <= af.crash_pitch_max_deg:
            reason = (f"pitch {pitch:.0f} deg on the ground (limits {af.crash_pitch_min_deg}.."
                      f"{af.crash_pitch_max_deg})")
        elif agl_ft < 0.0:
            reason = "the airframe went below the ground"
        else:
            return
        t_s = self._steps * self.dt_s
        self._crash = f"crashed at t = {t_s:.3f} s: {reason}"
        self._crash_truth = self.truth()
        raise FdmCrash(self._crash)

    @property
    def crash_reason(self):
        """Why the flight ended, or None while it goes on."""
        return self._crash

    def truth(self):
        if self._exec is None:
            raise RuntimeError("call reset_airborne or reset_on_ground first")
        if self._crash_truth is not None:
            return self._crash_truth
        (lat, lon, h_sl, h_agl, terrain, vn, ve, vd, phi, theta, psi, p, q, r, fx, fy, fz, vt, vc,
         alpha, beta, wow, p_psf, t_r, mass, rho_slug_ft3) = [n.get_double_value() for n in self._n_truth]
        k = M_PER_FT / mass
        sphi, cphi = math.sin(phi), math.cos(phi)
        sth, cth = math.sin(theta), math.cos(theta)
        spsi, cpsi = math.sin(psi), math.cos(psi)
        bn, be, bd = self.mag_field_ned_gauss
        # NED -> body FRD (ZYX Euler angles).
        mx = cth * cpsi * bn + cth * spsi * be - sth * bd
        my = (sphi * sth * cpsi - cphi * spsi) * bn + (sphi * sth * spsi + cphi * cpsi) * be + sphi * cth * bd
        mz = (cphi * sth * cpsi + sphi * spsi) * bn + (cphi * sth * spsi - sphi * cpsi) * be + cphi * cth * bd
        servo = Surfaces(*(s.position for s in self._servos))
        return Truth(
            t_s=self._steps * self.dt_s, lat_deg=lat, lon_deg=lon, alt_msl_m=h_sl * M_PER_FT,
            height_agl_m=h_agl * M_PER_FT, ground_msl_m=terrain * M_PER_FT,
            vn_mps=vn * M_PER_FT, ve_mps=ve * M_PER_FT, vd_mps=vd * M_PER_FT,
            roll_deg=math.degrees(phi), pitch_deg=math.degrees(theta),
            heading_deg=math.degrees(psi) % 360.0, p_rad_s=p, q_rad_s=q, r_rad_s=r,
            accel_body_mps2=(fx * k, fy * k, fz * k),
            airspeed_true_mps=vt * M_PER_FT, airspeed_cal_mps=vc * M_PER_FT,
            alpha_deg=alpha, beta_deg=beta, servo=servo, on_ground=wow > 0.5,
            mag_body_gauss=(mx, my, mz), pressure_pa=p_psf * PA_PER_PSF,
            temperature_c=(t_r - 491.67) * 5.0 / 9.0, crashed=self._crash is not None,
            air_density_kg_m3=rho_slug_ft3 * KG_M3_PER_SLUG_FT3)
