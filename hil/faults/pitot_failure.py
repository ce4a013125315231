"""Pitot (AMS5812) failure on the HA: mode dead (default: every I2C read fails; the HA holds its
last reading sensors.airspeed_timeout_s, then lacks state: takeover due), zero (reads 0 ft/s,
a blocked tube: airborne, that is further below the INS's groundspeed than sensors.max_wind_ftps,
so the HA takes it for a lying sensor, a failed read, not for a stall: takeover due as for dead)
or stuck (reads its last value: undetectable by design, no takeover due). Took effect when the
HA stepped on the failed reading."""
from hil.faults.base import Fault

MODES = ("dead", "zero", "stuck")


class PitotFailure(Fault):
    def __init__(self, *a):
        super().__init__(*a)
        self.mode = self.param("mode", "dead")
        if self.mode not in MODES:
            raise ValueError("pitot_failure: mode must be one of %s" % ", ".join(MODES))
        self.stuck = None
        self.steps = 0

    def board(self, t_s, b):
        if not self.active(t_s):
            self.stuck = b.airspeed_ftps
            return b
        if self.steps == 0:
            self.note(t_s, "pitot %s" % self.mode)
            if self.mode in ("dead", "zero"):
                self.due_s = t_s + float(self.ctx.limits["sensors"]["airspeed_timeout_s"])
        self.steps += 1
        if self.mode == "dead":
            return b._replace(airspeed_ok=False)
        return b._replace(airspeed_ftps=0.0 if self.mode == "zero" else (self.stuck or 0.0))

    def effect(self):
        return self.steps > 0, "the HA stepped %d periods on a %s pitot" % (self.steps, self.mode)


def inject(ctx, at_s, duration_s, params):
    return PitotFailure(ctx, at_s, duration_s, params)
