"""What climb, stall and bank share: an HP whose commands are valid (inside S_u, finite, a good
CRC, estimates sane) but steer the aircraft out of its envelope. The bad HP flies a target
attitude (reached slowly, see toward()) with its own simple loops on the truth attitude; the takeover becomes due when the
truth leaves S_x, passes the ceiling or falls to the stall (the verdict's own rule)."""
import math

from hil.faults.base import CommandFault


class SteeringFault(CommandFault):
    TARGET_PITCH_DEG = None
    TARGET_ROLL_DEG = None
    THROTTLE = None
    # How far the truth went after at_s, for the evidence: (the words, a %-format of the value;
    # max or min; the value of one truth sample).
    EXTREME = None

    def makes_due(self, m):
        return False  # the command itself is acceptable; the state it leads to is not

    def clamp(self, v, surface):
        """Inside S_u, and the elevator no more nose-up than the HA's pull limit (a pull past it is
        refused in flight as unsafe output, REASON_PULL: not a valid command)."""
        a = self.ctx.limits["actuators"]
        lim = 0.9 * a[surface + "_limit_deg"]
        low = -0.9 * a["elevator_pull_limit_deg"] if surface == "elevator" else -lim
        return max(low, min(lim, v))

    def toward(self, start, target, t_s):
        """The bad HP's target: from where it was when it started (at at_s, and again each time a
        restarted controller is given control) towards target at ramp_deg_s (default 5 deg/s): a
        slow drift, the hard case, not a violent manoeuvre the rate limits catch at once."""
        step = self.param("ramp_deg_s", 5.0) * (t_s - self.start_s)
        return min(target, start + step) if target >= start else max(target, start - step)

    def corrupt(self, t_s, m):
        tr = self.ctx.truth_at(t_s)
        if getattr(self, "start_pid", None) != self.ctx.hp_pid:  # this controller's first bad command
            self.start_pid, self.start_s = self.ctx.hp_pid, t_s
            self.start = (tr.pitch_deg, tr.roll_deg)
        if self.TARGET_PITCH_DEG is not None:  # elevator trailing edge down pitches down; q damps
            pitch = self.toward(self.start[0], self.param("pitch_deg", self.TARGET_PITCH_DEG), t_s)
            m.elevator_deg = self.clamp(0.8 * (tr.pitch_deg - pitch) + 0.3 * math.degrees(tr.q_rad_s), "elevator")
        if self.TARGET_ROLL_DEG is not None:   # aileron + rolls right; p damps
            roll = self.toward(self.start[1], self.param("roll_deg", self.TARGET_ROLL_DEG), t_s)
            m.aileron_deg = self.clamp(0.4 * (roll - tr.roll_deg) - 0.1 * math.degrees(tr.p_rad_s), "aileron")
        if self.THROTTLE is not None:
            m.throttle = self.param("throttle", self.THROTTLE)
        return m

    def effect(self):
        ok, why = super().effect()
        ex = self.extreme()
        return ok, why + ("; " + ex if ex else "")

    def extreme(self):
        if self.EXTREME is None:
            return ""
        words, worst, value = self.EXTREME
        series = [value(m) for t, m in self.ctx.truth_since(self.at_s)]
        return words % worst(series) if series else ""
