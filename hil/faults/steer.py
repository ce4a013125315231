"""What climb, stall and bank share: an HP whose commands are valid (inside S_u, finite, a good
CRC, estimates sane) but steer the aircraft out of its envelope. The bad HP flies a target
attitude with its own simple loops on the truth attitude; the takeover becomes due when the
truth leaves S_x, passes the ceiling or falls to the stall (the verdict's own rule)."""
from hil.faults.base import CommandFault


class SteeringFault(CommandFault):
    TARGET_PITCH_DEG = None
    TARGET_ROLL_DEG = None
    THROTTLE = None

    def makes_due(self, m):
        return False  # the command itself is acceptable; the state it leads to is not

    def clamp(self, v, surface):
        lim = 0.9 * self.ctx.limits["actuators"][surface + "_limit_deg"]
        return max(-lim, min(lim, v))

    def corrupt(self, t_s, m):
        tr = self.ctx.truth_at(t_s)
        pitch = self.param("pitch_deg", self.TARGET_PITCH_DEG) if self.TARGET_PITCH_DEG is not None else None
        roll = self.param("roll_deg", self.TARGET_ROLL_DEG) if self.TARGET_ROLL_DEG is not None else None
        if pitch is not None:  # elevator trailing edge down pitches down
            m.elevator_deg = self.clamp(1.0 * (tr.pitch_deg - pitch) - 0.2 * tr.q_rad_s * 57.2958, "elevator")
        if roll is not None:   # aileron + rolls right
            m.aileron_deg = self.clamp(0.5 * (roll - tr.roll_deg) - 0.05 * tr.p_rad_s * 57.2958, "aileron")
        if self.THROTTLE is not None:
            m.throttle = self.param("throttle", self.THROTTLE)
        return m

    def effect(self):
        ok, why = super().effect()
        ex = self.extreme()
        return ok, why + ("; " + ex if ex else "")

    def extreme(self):
        return ""
