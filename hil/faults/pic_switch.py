"""The pilot's PIC switch mid-fault: the HP crashes at at_s (SIGKILL), the HA takes over, and
switch_after_s later (default 1.0) the pilot sets the PIC/CIC switch to pilot for switch_s
(default 3.0) with the sticks hands off (at the transmitter's trims: hil.faults.base.rc_trimmed),
then back to computer. The pilot always wins: MANUAL is due the period the switch reads pilot.
Took effect when the crash did and the HA stepped on the switch in the pilot position."""
from hil.faults.base import Fault
from hil.faults.crash import Crash


class PicSwitch(Fault):
    def __init__(self, *a):
        super().__init__(*a)
        self.crash = Crash(self.ctx, self.at_s, -1.0, {})
        self.on_s = self.at_s + self.param("switch_after_s", 1.0)
        self.off_s = self.on_s + self.param("switch_s", 3.0)
        self.steps = 0
        self.first_pilot_s = None

    def on_step(self, t_s):
        self.crash.on_step(t_s)

    def pilot(self, t_s):
        return self.on_s - 1e-9 <= t_s < self.off_s - 1e-9

    def board(self, t_s, b):
        if not self.pilot(t_s):
            return b
        if self.steps == 0:
            self.first_pilot_s = t_s
            self.note(t_s, "PIC switch to pilot")
        self.steps += 1
        return b._replace(rc_pulses_us=b.rc_pulses_us[:4] + (2000,))

    def effect(self):
        ok, why = self.crash.effect()
        return ok and self.steps > 0, "%s; the HA stepped %d periods with the switch at pilot" % (why, self.steps)

    def takeover_due_s(self):
        return self.crash.takeover_due_s()


# What a campaign draws for this class (hil/campaigns/plan.py says how).
CAMPAIGN_PARAMS = {"switch_after_s": ("u", 0.3, 3.0), "switch_s": ("u", 1.0, 5.0)}
CAMPAIGN_DURATION = "none"


def inject(ctx, at_s, duration_s, params):
    return PicSwitch(ctx, at_s, duration_s, params)
