"""HP controller crash: SIGKILL of the controller (controller_<aircraft>) at at_s (duration ignored:
hp_supervisor restarts it when the HA asks). Took effect when the process is gone (reaped or a
zombie)."""
import os
import signal
import time

from hil.faults.base import Fault
from hil.proc_stat import DEAD, state


def controller_name(ctx):
    """The controller node's name as the log says it (controller_<aircraft>)."""
    return ctx.controller_node.lstrip("/")


def silence_hp(fault, t_s, verb):
    """The HP falls silent at t_s (the HA's deadline counts from here): the controller's pid to
    signal, or None, noted, when there is no controller to verb."""
    ctx = fault.ctx
    pid = ctx.controller_pid()
    ctx.hp_alive = False
    ctx.crashed_at = t_s
    if pid is None:
        fault.note(t_s, "%s not running: nothing to %s" % (controller_name(ctx), verb))
    return pid


def signal_until(pid, sig, states, timeout_s=10.0):
    """Sends sig to pid and waits up to timeout_s for /proc to show it in one of states (None:
    gone); returns the state it is in then."""
    os.kill(pid, sig)
    deadline = time.monotonic() + timeout_s
    while state(pid) not in states and time.monotonic() < deadline:
        time.sleep(0.005)
    return state(pid)


class Crash(Fault):
    SIGNAL = signal.SIGKILL

    def __init__(self, *a):
        super().__init__(*a)
        self.pid = None
        self.done = False
        self.confirmed = None

    def on_step(self, t_s):
        if self.done or t_s < self.at_s - 1e-9:
            return
        self.done = True
        self.pid = silence_hp(self, t_s, "signal")
        if self.pid is not None:
            self.signal_controller(t_s, self.pid)

    def signal_controller(self, t_s, pid):
        self.confirmed = signal_until(pid, signal.SIGKILL, DEAD) in DEAD
        self.note(t_s, "SIGKILL to %s (pid %d): %s" % (controller_name(self.ctx), pid, "gone" if self.confirmed else "still running"))
        self.ctx.event(t_s, "HP crash injected: SIGKILL to %s (pid %d)" % (controller_name(self.ctx), pid))

    def effect(self):
        if not self.confirmed:
            return False, "; ".join(self.notes) or "the flight ended before %.2f s" % self.at_s
        return True, "; ".join(self.notes)

    def takeover_due_s(self):
        return silent_hp_due_s(self.ctx) if self.confirmed else None


def silent_hp_due_s(ctx):
    """The HA's deadline miss after the HP fell silent at ctx.crashed_at: the end of the
    (late_periods_tolerated + 1)-th HA period in a row without a new command
    (verdicts.command_deadline). In lockstep the crash's own period is the first late one, so it
    is late_periods_tolerated periods after the crash; in real time the HA's ticks say, at
    whatever phase they run to the HP's timer. A flight that ended first: lockstep's rule."""
    from hil import verdicts
    r = ctx.regions
    miss = verdicts.command_deadline(verdicts.ha_periods(ctx), ctx.crashed_at, r.late_periods_tolerated)
    return miss[1] if miss is not None else ctx.crashed_at + r.late_periods_tolerated * r.period_s


# What a campaign draws for this class (hil/campaigns/plan.py says how).
CAMPAIGN_DURATION = "none"


def inject(ctx, at_s, duration_s, params):
    return Crash(ctx, at_s, duration_s, params)
