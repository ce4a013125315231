"""Pitot (AMS5812) failure on the HA, by mode:
- dead (default): every I2C read fails; the HA holds its last reading sensors.airspeed_timeout_s,
  then lacks state: takeover due then.
- zero: a blocked tube, reads 0 ft/s; airborne that is further below the INS's groundspeed than
  sensors.max_wind_ftps, so the HA takes it for a lying sensor, not for a stall: due as for dead.
- stuck: iced, holds one reading (value_ftps, default the reading at the fault).
- high, low: reads scale x the truth + offset_ftps (high: default +40 ft/s, more than any wind
  the HA allows; low: default x0.7), a miscalibrated, leaking or partly blocked probe.
For stuck, high and low the takeover falls due sensors.airspeed_timeout_s after the reading
becomes one no wind the HA allows can explain (impossible_reading below: a lying sensor, held no
longer than a failed read), or, reading low, at once at or below the HA's stall switch speed (the
HA must take over then, for the stall or for the sensor: either way the HA).
Took effect when the HA stepped on the failed reading.

pitot_stuck and pitot_high are this fault with the mode fixed (their own classes, so campaigns
deal them on their own)."""
import math

from hil.faults.base import Fault
from stack_common.units import FT_PER_M

MODES = ("dead", "zero", "stuck", "high", "low")
RHO0 = 1.225


def impossible_reading(limits, truth, reading_ftps, margin_ftps):
    """Why a pitot reading (calibrated, ft/s) cannot be the airspeed in any wind the HA allows,
    or None: the true airspeed differs from the inertial speed |v| by at most the wind, so a
    true airspeed (the reading through the true density) outside |v| +- sensors.max_wind_ftps
    (+ margin_ftps for the HA's sensor errors) is a lying sensor. Airborne only."""
    if truth.on_ground:
        return None
    v_ftps = math.sqrt(truth.vn_mps ** 2 + truth.ve_mps ** 2 + truth.vd_mps ** 2) * FT_PER_M
    tas_ftps = reading_ftps * math.sqrt(RHO0 / truth.air_density_kg_m3)
    band = float(limits["sensors"]["max_wind_ftps"]) + margin_ftps
    if tas_ftps > v_ftps + band:
        return "reads %.1f ft/s (TAS %.1f), above |v| %.1f + %.1f" % (reading_ftps, tas_ftps, v_ftps, band)
    if tas_ftps < v_ftps - band:
        return "reads %.1f ft/s (TAS %.1f), below |v| %.1f - %.1f" % (reading_ftps, tas_ftps, v_ftps, band)
    return None


class PitotFailure(Fault):
    MODE = None  # a fixed mode (pitot_stuck, pitot_high); None: the mode parameter

    def __init__(self, *a):
        super().__init__(*a)
        self.mode = self.MODE or self.param("mode", "dead")
        if self.mode not in MODES:
            raise ValueError("pitot_failure: mode must be one of %s" % ", ".join(MODES))
        self.stuck = self.params.get("value_ftps")
        self.stuck = None if self.stuck is None else float(self.stuck)
        self.scale = self.param("scale", {"low": 0.7}.get(self.mode, 1.0))
        self.offset_ftps = self.param("offset_ftps", 40.0 if self.mode == "high" else 0.0)
        # The HA's pitot noise and offset, its INS's velocity error and its own idea of density
        # make a reading just outside the band undecidable for it: due only clearly outside.
        self.margin_ftps = self.param("due_margin_ftps", 5.0)
        st = self.ctx.limits["state"]
        self.switch_ftps = float(st["stall_speed_ftps"]) * float(st["stall_switch_multiple"])
        self.last = None
        self.steps = 0
        self.worst = None

    def reading(self, b):
        if self.mode == "zero":
            return 0.0
        if self.mode == "stuck":
            if self.stuck is None:
                self.stuck = self.last if self.last is not None else b.airspeed_ftps
            return self.stuck
        return max(0.0, self.scale * b.airspeed_ftps + self.offset_ftps)

    def board(self, t_s, b):
        if not self.active(t_s):
            self.last = b.airspeed_ftps
            return b
        if self.steps == 0:
            self.note(t_s, "pitot %s%s" % (self.mode, " at %.1f ft/s" % self.reading(b) if self.mode == "stuck" else
                                           " (x%g %+g ft/s)" % (self.scale, self.offset_ftps)
                                           if self.mode in ("high", "low") else ""))
            if self.mode in ("dead", "zero"):
                self.due_s = t_s + float(self.ctx.limits["sensors"]["airspeed_timeout_s"])
        self.steps += 1
        if self.mode == "dead":
            return b._replace(airspeed_ok=False)
        r = self.reading(b)
        if self.mode in ("stuck", "high", "low") and self.due_s is None:
            self.check_due(t_s, b.airspeed_ftps, r)
        return b._replace(airspeed_ftps=r)

    def check_due(self, t_s, healthy_ftps, r):
        tr = self.ctx.truth_at(t_s)
        lim = self.ctx.limits
        why = impossible_reading(lim, tr, r, self.margin_ftps)
        if why is not None and impossible_reading(lim, tr, healthy_ftps, 0.0) is None:
            # A lying reading is a failed read: the HA may hold the last good one as long as it
            # holds one through an I2C glitch (sensors.airspeed_timeout_s), as for dead and zero.
            self.due_s = t_s + float(lim["sensors"]["airspeed_timeout_s"])
            self.note(t_s, "impossible reading, takeover due at %.2f s: %s (a healthy pitot: %.1f ft/s)" % (
                self.due_s, why, healthy_ftps))
        elif not tr.on_ground and r <= self.switch_ftps < healthy_ftps:
            self.due_s = t_s
            self.note(t_s, "takeover due: reads %.1f ft/s, at or below the stall switch speed %.1f "
                           "(a healthy pitot: %.1f ft/s)" % (r, self.switch_ftps, healthy_ftps))

    def effect(self):
        return self.steps > 0, "the HA stepped %d periods on a %s pitot; %s" % (self.steps, self.mode,
                                                                              "; ".join(self.notes[:3]))


def inject(ctx, at_s, duration_s, params):
    return PitotFailure(ctx, at_s, duration_s, params)


def draw_params(rng):
    """A campaign's draw: dead, blocked, or reading low by a scale (stuck and high are classes of
    their own)."""
    mode = rng.choice(("dead", "zero", "low"))
    return {"mode": mode, "scale": round(rng.uniform(0.5, 0.85), 3)} if mode == "low" else {"mode": mode}
