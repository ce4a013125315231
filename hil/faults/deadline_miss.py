"""Deadline misses: the HP's commands come late. A hiccup of delay_periods (0.5 to 3; default 2)
HA periods holds the commands computed in it and hands them to the link in a burst when it ends
(the HP caught up), so ceil(delay_periods) periods pass without their command. Single by default;
repeat_every_periods > 0 starts a hiccup that often for the rest of the window. A takeover is due
when a hiccup leaves more periods without a command than limits.yaml's late_periods_tolerated:
the deadline is then the last tolerated period's end, as for a crash."""
import math

from hil.faults.base import Fault


class DeadlineMiss(Fault):
    NEEDS_RELAY = True

    def __init__(self, *a):
        super().__init__(*a)
        self.delay = self.param("delay_periods", 2.0)
        if not 0.0 < self.delay <= 10.0:
            raise ValueError("deadline_miss: delay_periods must be in (0, 10]")
        self.every = int(self.param("repeat_every_periods", 0.0))
        self.held = []
        self.release_at = None
        self.next_start = self.at_s
        self.hiccups = []       # start times
        self.missed = []        # HA periods that went without their (computed) command
        self.pending_miss = None

    def command(self, t_s, msg):
        period = self.ctx.regions.period_s
        if self.release_at is None and self.active(t_s) and t_s >= self.next_start - 1e-9 and msg is not None:
            missed = int(math.ceil(self.delay - 1e-9))
            self.release_at = t_s + missed * period
            self.hiccups.append(t_s)
            self.next_start = t_s + self.every * period if self.every > 0 else float("inf")
            if len(self.hiccups) == 1:
                self.note(t_s, "HP late by %g periods (%d without a command)%s" % (
                    self.delay, missed, ", every %d periods" % self.every if self.every else ""))
            if missed > self.ctx.regions.late_periods_tolerated and self.due_s is None:
                self.due_s = t_s + self.ctx.regions.late_periods_tolerated * period
        if self.release_at is not None:
            if t_s < self.release_at - 1e-9:
                if msg is not None:
                    self.held.append(msg)
                    self.pending_miss = t_s
                return []
            out = self.held + ([] if msg is None else [msg])
            self.held, self.release_at = [], None
            return out
        return [] if msg is None else [msg]

    def after_step(self, t_s, reply):
        if self.pending_miss == t_s:
            # The HA stepped with nothing new on its link while the HP's command was held.
            if reply.commands_received == self.ctx.relayed:
                self.missed.append(t_s)
            self.pending_miss = None

    def effect(self):
        if not self.missed:
            return False, "no HA period went without its command"
        return True, "%d hiccups, %d HA periods without their command (first at %.2f s)" % (
            len(self.hiccups), len(self.missed), self.missed[0])


# What a campaign draws for this class (hil/campaigns/plan.py says how).
CAMPAIGN_PARAMS = {"delay_periods": ("u", 0.5, 3.0), "repeat_every_periods": (0, 0, 5, 20)}


def inject(ctx, at_s, duration_s, params):
    return DeadlineMiss(ctx, at_s, duration_s, params)
