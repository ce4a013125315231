"""Stale replay: an old valid command (params: age_s, default 1.0) is sent again in place of the
current one, unchanged (its own sequence number, stamp and CRC), every period of the window: a
replay from a buffer that stopped advancing."""
from collections import deque

from hil.faults.base import CommandFault, copy_command


class StaleReplay(CommandFault):
    RESIGN = False

    def __init__(self, *a):
        super().__init__(*a)
        self.old = deque()
        self.replayed = None

    def command(self, t_s, msg):
        if msg is not None and t_s < self.at_s - 1e-9:
            self.old.append((t_s, copy_command(msg)))
            while self.old and self.old[0][0] < t_s - 10.0:
                self.old.popleft()
        return super().command(t_s, msg)

    def corrupt(self, t_s, m):
        if self.replayed is None:
            age = self.param("age_s", 1.0)
            older = [c for ts, c in self.old if ts <= self.at_s - age + 1e-9]
            if not older:
                return None
            self.replayed = older[-1]
        return copy_command(self.replayed)


# What a campaign draws for this class (hil/campaigns/plan.py says how).
CAMPAIGN_PARAMS = {"age_s": ("u", 0.2, 3.0)}


def inject(ctx, at_s, duration_s, params):
    return StaleReplay(ctx, at_s, duration_s, params)
