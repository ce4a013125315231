"""Frozen output: the HP's last command before at_s is sent again, unchanged (same sequence number,
stamp and CRC), every period of the window."""
from hil.faults.base import CommandFault, copy_command


class Frozen(CommandFault):
    RESIGN = False

    def __init__(self, *a):
        super().__init__(*a)
        self.last_good = None

    def command(self, t_s, msg):
        if msg is not None and t_s < self.at_s - 1e-9:
            self.last_good = copy_command(msg)
        return super().command(t_s, msg)

    def corrupt(self, t_s, m):
        return None if self.last_good is None else copy_command(self.last_good)


def inject(ctx, at_s, duration_s, params):
    return Frozen(ctx, at_s, duration_s, params)
