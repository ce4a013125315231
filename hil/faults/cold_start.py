"""Power-up with no GNSS fix and a dead pitot (issue 22, F6): from power-up until at_s the VN-200
has no fix yet (aligning, no satellites, on both its ports) and every AMS5812 read fails, and the
aircraft stays parked hold_s (default 3 s) longer than that before the usual airborne start. The
HA used to spin the motor to its trim on the ground ("blind counts as airborne"). Power-up is on
the ground until a sign of flight: the motor must idle on the ground the whole time, home latch
once the fix and the pitot are there, and the flight go on as usual after the airborne start. No
takeover is due. Took effect when the HA stepped parked with the pitot dead and no INS state."""
from hil import ha_channel
from hil.faults.base import Fault

INS_STATUS_ALIGNING_NO_FIX = 0x0001  # mode 1 (aligning), GNSS fix bit clear


class ColdStart(Fault):
    def __init__(self, *a):
        super().__init__(*a)
        self.hold_s = self.param("hold_s", 3.0)
        # Parked until the fix and the pitot have been there hold_s: the airborne start waits.
        self.ctx.ground_s = max(self.ctx.ground_s, self.at_s + self.hold_s)
        for port in (self.ctx.ha_vn, self.ctx.hp_vn):
            port.solution_filter = self.solution
        self.blind_steps = 0
        self.ground_steps = 0
        self.max_ground_throttle = None
        self.home_s = None

    def active(self, t_s):
        return t_s < self.at_s - 1e-9  # from power-up until at_s

    def solution(self, sensor_t_s, sol):
        if sensor_t_s < self.at_s - 1e-9:
            sol.ins_status, sol.gps_fix, sol.num_sats = INS_STATUS_ALIGNING_NO_FIX, 0, 0
        return sol

    def board(self, t_s, b):
        if not self.active(t_s):
            return b
        if not self.notes:
            self.note(t_s, "power-up: no GNSS fix, pitot dead until %.2f s; parked until %.2f s" % (
                self.at_s, self.ctx.ground_s))
        return b._replace(airspeed_ok=False)

    def after_step(self, t_s, reply):
        if t_s < self.ctx.ground_s - 1e-9:
            self.ground_steps += 1
            th = reply.applied[3]
            self.max_ground_throttle = th if self.max_ground_throttle is None else max(self.max_ground_throttle, th)
            if self.active(t_s) and not reply.flags & ha_channel.R_STATE_VALID:
                self.blind_steps += 1
        if self.home_s is None and reply.flags & ha_channel.R_HOME:
            self.home_s = t_s
            self.note(t_s, "the HA latched home")

    def effect(self):
        return self.blind_steps > 0, (
            "%d periods parked with the pitot dead and no INS state, %d parked in all; highest throttle parked "
            "%s; home latched at %s s" % (self.blind_steps, self.ground_steps, self.max_ground_throttle, self.home_s))

    def detail(self):
        return {"blind_steps": self.blind_steps, "ground_steps": self.ground_steps,
                "max_ground_throttle": self.max_ground_throttle, "home_s": self.home_s}


# What a campaign draws for this class (hil/campaigns/plan.py says how).
CAMPAIGN_DURATION = "none"


def inject(ctx, at_s, duration_s, params):
    return ColdStart(ctx, at_s, duration_s, params)
