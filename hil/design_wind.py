"""The aircraft's design wind (limits.yaml design_wind, with sensors.max_wind_ftps the steady
wind): the air in which a flight claims the Simplex property. A flight whose air goes beyond it
is judged on survival alone (no crash, no unsafe command), in a table of its own: no aircraft
holds its wing below the stall through a wind that takes its airspeed faster than a dive can
give it back (HiL campaign seed 24: an 11.4 m/s headwind turned into a 12.8 m/s tailwind in 3 s,
26 ft/s^2 along the track; 12 m/s from behind in 0.5 s onto a 60 ft/s cruise).

    design = DesignWind.load(limits_doc, airframe_doc)
    design.steady(wind_mps, turbulence)               -> [] or the reasons it is beyond
    design.change(base_ne_mps, target_ne_mps, ramp_s, veer_deg_s, turbulence)
"""
import math

from stack_common.units import FT_PER_M, G_FTPS2

TURBULENCE = ("none", "light", "moderate")


class DesignWindError(ValueError):
    pass


class DesignWind:
    def __init__(self, steady_ftps, gust_ftps, shear_ftps2, turbulence):
        self.steady_ftps = steady_ftps
        self.gust_ftps = gust_ftps
        self.shear_ftps2 = shear_ftps2
        self.turbulence = turbulence

    @classmethod
    def load(cls, limits, airframe):
        """From limits.yaml and airframe.yaml (parsed), refusing a design wind the airframe cannot
        fly: a gust past the cruise's margin over the HA's stall switch speed, or a shear faster
        than a dive at the safety controller's pitch limit regains."""
        try:
            dw = limits["design_wind"]
            steady = float(limits["sensors"]["max_wind_ftps"])
            gust, shear, turb = float(dw["gust_ftps"]), float(dw["shear_ftps2"]), str(dw["turbulence"])
            switch_ftps = float(limits["state"]["stall_speed_ftps"]) * float(limits["state"]["stall_switch_multiple"])
            pitch_deg = float(limits["safety_controller"]["pitch_cmd_limit_deg"])
            cruise_ftps = float(airframe["design_point"]["airspeed_ftps"])
        except (KeyError, TypeError, ValueError) as err:
            raise DesignWindError("design_wind: cannot read it from limits.yaml and airframe.yaml (%s)" % err)
        margin = cruise_ftps - switch_ftps
        if not 0.0 < gust <= margin:
            raise DesignWindError("design_wind.gust_ftps = %g: a gust from behind at the %g ft/s cruise must leave "
                                  "the wing above the %.1f ft/s stall switch speed (at most %.1f)"
                                  % (gust, cruise_ftps, switch_ftps, margin))
        regain = G_FTPS2 * math.sin(math.radians(pitch_deg))
        if not 0.0 < shear <= regain:
            raise DesignWindError("design_wind.shear_ftps2 = %g: faster than a dive at pitch_cmd_limit_deg (%g deg) "
                                  "regains, %.1f ft/s^2" % (shear, pitch_deg, regain))
        if turb not in TURBULENCE:
            raise DesignWindError("design_wind.turbulence = %s: one of %s" % (turb, ", ".join(TURBULENCE)))
        return cls(steady, gust, shear, turb)

    def _turbulence(self, level):
        if TURBULENCE.index(level) > TURBULENCE.index(self.turbulence):
            return ["%s turbulence (design: %s)" % (level, self.turbulence)]
        return []

    def steady(self, mps, turbulence):
        """Why a steady wind of mps with this turbulence is beyond the design wind ([]: within)."""
        why = self._turbulence(turbulence)
        if mps * FT_PER_M > self.steady_ftps + 1e-6:
            why.insert(0, "steady %.1f ft/s (design: %g)" % (mps * FT_PER_M, self.steady_ftps))
        return why

    def change(self, base_ne_mps, target_ne_mps, ramp_s, veer_deg_s, turbulence):
        """Why a change of the wind from base to target (north, east m/s) over ramp_s, veering
        after at veer_deg_s, is beyond the design wind ([]: within). The change may be up to the
        gust at once, and the shear rate beyond it."""
        target_mps = math.hypot(*target_ne_mps)
        why = self.steady(target_mps, turbulence)
        delta_ftps = math.hypot(target_ne_mps[0] - base_ne_mps[0], target_ne_mps[1] - base_ne_mps[1]) * FT_PER_M
        allowed = self.gust_ftps + self.shear_ftps2 * max(0.0, ramp_s)
        if delta_ftps > allowed + 1e-6:
            why.append("a change of %.1f ft/s in %g s (design: %g ft/s at once, %g ft/s^2 beyond)"
                       % (delta_ftps, ramp_s, self.gust_ftps, self.shear_ftps2))
        veer_ftps2 = target_mps * FT_PER_M * math.radians(abs(veer_deg_s))
        if veer_ftps2 > self.shear_ftps2 + 1e-6:
            why.append("a veer of %.1f ft/s^2 (design: %g)" % (veer_ftps2, self.shear_ftps2))
        return why
