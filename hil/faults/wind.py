"""The wind changes in flight: a gust front, a shear or a wind shift, onto whatever wind the
flight started in (hil.launch's wind_mps, wind_from_deg, turbulence).

At the fault the wind swings from the flight's to mps (default 9 m/s, 29.5 ft/s: just inside
sensors.max_wind_ftps) from from_rel_deg relative to the aircraft's heading at that moment
(default 180: from straight behind, the tailwind turn: the airspeed drops by the wind at once
and the aircraft must dive or add power to get it back), or from from_deg (true) when given;
over ramp_s (default 1 s; the wind vector blended, as a front passes), then it keeps veering at
veer_deg_s (default 0), with turbulence at its own level when given. At the end of the window
it swings back over ramp_s. Nothing is wrong with the HP or the HA: the class makes no takeover
due; the verdict's truth does (the aircraft falling to the stall speed while the HP flies, or
leaving S_x). Took effect when the HA stepped in the changed wind."""
import math

from hil.faults.base import Fault
from hil.fdm import Wind


def to_vector(w):
    """(north, east) in m/s of the air's motion (where it blows to)."""
    r = math.radians(w.mean_from_deg)
    return -w.mean_mps * math.cos(r), -w.mean_mps * math.sin(r)


def from_vector(n, e, turbulence):
    mps = math.hypot(n, e)
    return Wind(mean_from_deg=(math.degrees(math.atan2(-e, -n)) % 360.0) if mps > 0.0 else 0.0,
                mean_mps=mps, turbulence=turbulence)


class WindShift(Fault):
    def __init__(self, *a):
        super().__init__(*a)
        self.mps = self.param("mps", 9.0)
        self.ramp_s = max(0.0, self.param("ramp_s", 1.0))
        self.veer_deg_s = self.param("veer_deg_s", 0.0)
        self.base = None      # the flight's wind when the fault began
        self.target = None
        self.steps = 0
        self.last = None

    def wind_at(self, t_s):
        """The wind of this instant: base -> target over ramp_s from at_s, veering after; back to
        base over ramp_s from the end of the window."""
        if self.ended(t_s):
            u = 1.0 - min(1.0, (t_s - (self.at_s + self.duration_s)) / self.ramp_s) if self.ramp_s > 0 else 0.0
            veer = self.veer_deg_s * max(0.0, self.duration_s - self.ramp_s)
        else:
            u = min(1.0, (t_s - self.at_s) / self.ramp_s) if self.ramp_s > 0 else 1.0
            veer = self.veer_deg_s * max(0.0, t_s - self.at_s - self.ramp_s)
        tgt = Wind((self.target.mean_from_deg + veer) % 360.0, self.target.mean_mps, self.target.turbulence)
        bn, be = to_vector(self.base)
        tn, te = to_vector(tgt)
        turb = self.target.turbulence if u > 0.0 else self.base.turbulence
        return from_vector(bn + u * (tn - bn), be + u * (te - be), turb)

    def on_step(self, t_s):
        if t_s < self.at_s - 1e-9:
            return
        if self.base is None:
            tr = self.ctx.truth_at(t_s)
            self.base = self.ctx.wind
            from_deg = self.params.get("from_deg")
            from_deg = (tr.heading_deg + self.param("from_rel_deg", 180.0)) % 360.0 if from_deg is None \
                else float(from_deg) % 360.0
            self.target = Wind(from_deg, self.mps, self.params.get("turbulence", self.base.turbulence))
            self.note(t_s, "wind from %.0f deg at %.1f m/s (%s turbulence) onto %.1f m/s from %.0f deg, heading "
                           "%.0f deg, over %.2f s%s" % (from_deg, self.mps, self.target.turbulence, self.base.mean_mps,
                                                        self.base.mean_from_deg, tr.heading_deg, self.ramp_s,
                                                        ", veering %g deg/s" % self.veer_deg_s if self.veer_deg_s else ""))
            design = getattr(self.ctx, "design_wind", None)
            self.beyond = [] if design is None else design.change(
                to_vector(self.base), to_vector(self.target), self.ramp_s, self.veer_deg_s, self.target.turbulence)
            if self.beyond:
                self.note(t_s, "beyond the design wind: " + "; ".join(self.beyond))
        w = self.wind_at(t_s)
        if w != self.last:
            self.ctx.set_wind(t_s, w)
            self.last = w

    def beyond_design_wind(self):
        """Why the change went beyond the aircraft's design wind (hil/design_wind.py; []: within)."""
        return list(getattr(self, "beyond", []))

    def after_step(self, t_s, reply):
        if self.active(t_s) and self.last is not None:
            self.steps += 1

    def effect(self):
        if not self.steps:
            return False, "the wind never changed while the HA stepped"
        cal = [(p.t_s, p.airspeed_cal_ftps) for p in self.ctx.records
               if self.at_s - 1e-9 <= p.t_s <= self.at_s + self.ramp_s + 5.0]
        low = min(cal, key=lambda x: x[1]) if cal else None
        return True, "the HA stepped %d periods in the changed wind; %s%s" % (
            self.steps, "; ".join(self.notes[:1]),
            "; lowest calibrated airspeed %.1f ft/s at %.2f s (%.1f at the fault)" % (low[1], low[0], cal[0][1])
            if low else "")


# What a campaign draws for this class (hil/campaigns/plan.py says how).
CAMPAIGN_DURATION = "long"


def draw_params(rng):
    """A front from anywhere, half of them from behind (the tailwind turn), 2-14 m/s (up to 1.5x
    sensors.max_wind_ftps), sudden or over up to 10 s, a fifth veering, some with turbulence:
    inside the aircraft's design wind and beyond it (hil/design_wind.py decides which in flight,
    from the wind the change starts from)."""
    p = {"mps": round(rng.uniform(2.0, 14.0), 2), "ramp_s": rng.choice((0.0, 0.5, 1.0, 3.0, 6.0, 10.0))}
    if rng.random() < 0.5:
        p["from_rel_deg"] = round(rng.uniform(150.0, 210.0), 1)
    else:
        p["from_deg"] = round(rng.uniform(0.0, 360.0), 1)
    if rng.random() < 0.2:
        p["veer_deg_s"] = round(rng.uniform(-10.0, 10.0), 2)
    if rng.random() < 0.3:
        p["turbulence"] = rng.choice(("light", "moderate"))
    return p


def inject(ctx, at_s, duration_s, params):
    return WindShift(ctx, at_s, duration_s, params)

