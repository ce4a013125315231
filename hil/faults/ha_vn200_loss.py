"""VN-200 loss on the HA side (the HA's own INS, the Due's Serial1): no packet reaches the HA's
port for the window. Took effect when the HA's count of INS solutions used stood still. A
takeover is due (the HA cannot judge the state, so it does not trust the HP) once its newest
solution is older than limits.yaml's sensors.state_timeout_s."""
from hil.faults.base import Fault


class HaVn200Loss(Fault):
    def __init__(self, *a):
        super().__init__(*a)
        self.first_s = None
        self.used_at_start = None
        self.stood_still = 0
        self.steps = 0

    def ha_vn_ok(self, t_s):
        if self.active(t_s):
            if self.first_s is None:
                self.first_s = t_s
                self.note(t_s, "HA VN-200 port silent")
                # The last packet went out in the period before: stale state_timeout_s after it.
                prev = t_s - self.ctx.regions.period_s
                self.due_s = prev + float(self.ctx.limits["sensors"]["state_timeout_s"])
            return False
        return True

    def after_step(self, t_s, reply):
        if self.active(t_s):
            self.steps += 1
            if self.used_at_start is None:
                self.used_at_start = reply.ins_solutions_used
            elif reply.ins_solutions_used == self.used_at_start:
                self.stood_still += 1

    def effect(self):
        if not self.steps or self.stood_still + 1 < self.steps:
            return False, "HA INS solutions still counted during %d of %d periods" % (self.steps - self.stood_still, self.steps)
        return True, "the HA used no INS solution for %d periods from %.2f s" % (self.steps, self.first_s)


def inject(ctx, at_s, duration_s, params):
    return HaVn200Loss(ctx, at_s, duration_s, params)
