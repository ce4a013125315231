"""HP controller hang: SIGSTOP of the controller (controller_<aircraft>) at at_s (its process and
ROS connections stay up, it only stops answering). With a duration >= 0 it gets SIGCONT after it
(if it still exists: hp_supervisor kills a hung controller when the HA asks for a restart);
negative: never. Took effect when /proc shows the process stopped (state T)."""
import os
import signal

from hil.faults.base import Fault
from hil.faults.crash import controller_name, signal_until, silence_hp, silent_hp_due_s
from hil.proc_stat import state

STOPPED = ("T", "t")  # proc(5): stopped by a signal, or by a tracer


class Hang(Fault):
    def __init__(self, *a):
        super().__init__(*a)
        self.pid = None
        self.done = False
        self.confirmed = False
        self.resumed = False

    def on_step(self, t_s):
        if not self.done and t_s >= self.at_s - 1e-9:
            self.done = True
            self.pid = pid = silence_hp(self, t_s, "stop")
            if pid is None:
                return
            st = signal_until(pid, signal.SIGSTOP, STOPPED + (None,))
            self.confirmed = st in STOPPED
            self.note(t_s, "SIGSTOP to %s (pid %d): state %s" % (controller_name(self.ctx), pid, st))
            self.ctx.event(t_s, "HP hang injected: SIGSTOP to %s (pid %d)" % (controller_name(self.ctx), pid))
        elif self.done and self.pid and not self.resumed and self.ended(t_s):
            self.resumed = True
            if state(self.pid) in STOPPED:
                os.kill(self.pid, signal.SIGCONT)
                self.note(t_s, "SIGCONT to %s (pid %d)" % (controller_name(self.ctx), self.pid))
            else:
                self.note(t_s, "no SIGCONT: pid %d is gone (hp_supervisor restarted it)" % self.pid)

    def effect(self):
        return self.confirmed, "; ".join(self.notes) or "the flight ended before %.2f s" % self.at_s

    def takeover_due_s(self):
        return silent_hp_due_s(self.ctx) if self.confirmed else None


def inject(ctx, at_s, duration_s, params):
    return Hang(ctx, at_s, duration_s, params)
