"""The HA reset in flight, as a watchdog or brown-out reset resets the Due (issue 22, F5): at at_s
the SIL restarts with its RAM cleared (the core, the INS adapter and the link device afresh, the
link silent until the host asks for topics again) and only the board's retained words kept (the
SAM3X's backup registers). Home can latch only on the ground, so an HA that forgot it would refuse
every solution for the rest of the flight, lock the healthy HP out and fly without a height. It
must take home and its airborne latch back, have a valid state again at once, and hand the servos
back to the HP after the stable window. The reset itself puts the HA on the servos: no takeover is
due by the class. Took effect when the HA stepped after the reset."""
from drone_ros.msg import DecisionStatus
from hil import ha_channel
from hil.faults.base import Fault


class HaReset(Fault):
    def __init__(self, *a):
        super().__init__(*a)
        self.reset_t_s = None
        self.home_before = False
        self.steps_after = 0
        self.home_steps_after = 0
        self.valid_steps_after = 0
        self.first_valid_s = None
        self.hp_back_s = None

    def on_step(self, t_s):
        if self.reset_t_s is not None or t_s < self.at_s - 1e-9:
            return
        self.reset_t_s = t_s
        if self.ctx.realtime:
            self.ctx.chan.send_reset()
            self.note(t_s, "HA reset (RAM cleared, retained words kept)")
            return
        r = self.ctx.chan.reset()
        self.note(t_s, "HA reset (RAM cleared, retained words kept): home %s, controller %d" % (
            "kept" if r.flags & ha_channel.R_HOME else "lost", r.controller))

    def after_step(self, t_s, reply):
        if self.reset_t_s is None:
            self.home_before = bool(reply.flags & ha_channel.R_HOME)
            return
        self.steps_after += 1
        if reply.flags & ha_channel.R_HOME:
            self.home_steps_after += 1
        if reply.flags & ha_channel.R_STATE_VALID:
            self.valid_steps_after += 1
            if self.first_valid_s is None:
                self.first_valid_s = t_s
        if self.hp_back_s is None and reply.controller == DecisionStatus.CONTROLLER_HP:
            self.hp_back_s = t_s
            self.note(t_s, "the HP has the servos again, %.2f s after the reset" % (t_s - self.reset_t_s))

    def effect(self):
        if self.reset_t_s is None or self.steps_after == 0:
            return False, "the HA was never reset"
        return True, ("HA reset at %.2f s (home before: %s); after it, %d periods: home in %d, a valid state in "
                      "%d (first at %s s), the HP back at %s s" % (
                          self.reset_t_s, self.home_before, self.steps_after, self.home_steps_after,
                          self.valid_steps_after, self.first_valid_s, self.hp_back_s))

    def detail(self):
        """What the story test reads (summary "fault.evidence" says the same in words)."""
        return {"reset_s": self.reset_t_s, "home_before": self.home_before, "steps_after": self.steps_after,
                "home_steps_after": self.home_steps_after, "valid_steps_after": self.valid_steps_after,
                "first_valid_s": self.first_valid_s, "hp_back_s": self.hp_back_s}


# What a campaign draws for this class (hil/campaigns/plan.py says how).
CAMPAIGN_DURATION = "none"


def inject(ctx, at_s, duration_s, params):
    return HaReset(ctx, at_s, duration_s, params)
