"""What a HiL flight leaves behind for its judges, by name: the simulator writes it, the verdicts
(hil.verdicts) and the fault classes' own checks read it.

- `Period`: one HA period on the simulator's time axis, the truth and the HA's reply of it. In
  lockstep there is one per step; real time keeps one per simulator step too.
- `HaPeriod`: one period as the HA itself counted it (lockstep: the same periods; real time: the
  HA's own ticks from its replies, which the simulator sees up to a step late).

Who flew when is computed once, by report_core.switches.stretches over any controller series:
the verdicts' `who_flew` from the periods and the flight report's runs from the bag's
DecisionStatus both call it."""
from typing import NamedTuple


class Period(NamedTuple):
    t_us: int  # simulated time of the period
    truth: object  # drone_ros/HilTruth as published on /hil/truth (feet, degrees)
    reply: object  # hil.ha_channel's reply: controller, reasons, applied surfaces, counters
    cmd_seq: object  # the HP command's sequence number the HA took, or None
    airspeed_cal_ftps: float  # calibrated airspeed of the truth (what a pitot would read)

    @property
    def t_s(self):
        return self.t_us * 1e-6


class HaPeriod(NamedTuple):
    t_s: float
    commands_received: int  # the HA link's count of HP commands delivered so far
    controller: int  # msg/DecisionStatus.msg CONTROLLER_*
    reasons_at_switch: int
