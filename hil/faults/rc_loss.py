"""RC loss: the receiver loses the transmitter for the window; its channels are no longer
captured (RC_VALID cleared) and what they read is noise, the PIC/CIC channel included (params
pic_us, default 2000: it reads "pilot"). The HA must not hand the servos to that. Took effect
when the HA stepped on the lost receiver; no takeover is due (the computer stays in command)."""
from hil.faults.base import Fault


class RcLoss(Fault):
    def __init__(self, *a):
        super().__init__(*a)
        self.steps = 0

    def board(self, t_s, b):
        if not self.active(t_s):
            return b
        if self.steps == 0:
            self.note(t_s, "RC receiver lost (channels invalid, PIC channel reads %d us)" % self.param("pic_us", 2000.0))
        self.steps += 1
        return b._replace(rc_valid=False, rc_pulses_us=(1900, 1000, 2000, 1000, int(self.param("pic_us", 2000.0))))

    def effect(self):
        return self.steps > 0, "the HA stepped %d periods without a valid RC receiver" % self.steps


def inject(ctx, at_s, duration_s, params):
    return RcLoss(ctx, at_s, duration_s, params)
