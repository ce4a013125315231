"""Who flew when: the runs of one controller and the switches between them, from the HA's
DecisionStatus stream (the HA's own record of its decisions)."""
from dataclasses import dataclass, field
from typing import List

import numpy as np

from . import definitions


@dataclass
class Run:
    controller: str
    start_s: float
    end_s: float  # the next switch, or the last decision of the log


@dataclass
class Switch:
    t_s: float
    from_controller: str
    to_controller: str
    reasons: List[str] = field(default_factory=list)  # why, as the HA reported it
    duration_s: float = 0.0  # how long the new controller stayed in force
    until_end: bool = False  # the log ended with it still in force
    stable_for_s: float = 0.0  # how long the HP command had been valid at the switch


def runs(log):
    controller = log.decision.controller.astype(int)
    t = log.decision.t
    starts = np.concatenate(([0], np.flatnonzero(np.diff(controller)) + 1))
    out = []
    for i, start in enumerate(starts):
        end_s = t[starts[i + 1]] if i + 1 < len(starts) else t[-1]
        out.append(Run(_name(log, controller[start]), float(t[start]), float(end_s)))
    return out


def switches(log):
    """Every change of the controller in force. A switch to an HA mode carries the checks that
    caused it (reasons_at_switch); any other switch carries the checks failing in that period."""
    d = log.decision
    all_runs = runs(log)
    index_of_start = np.concatenate(([0], np.flatnonzero(np.diff(d.controller.astype(int))) + 1))
    ha_modes = {log.controller_value.get(n) for n in ("HA", "HA_LATCHED")}
    out = []
    for k in range(1, len(all_runs)):
        i = index_of_start[k]
        to_value = int(d.controller[i])
        mask = d.reasons_at_switch[i] if to_value in ha_modes else d.reasons[i]
        out.append(Switch(
            t_s=all_runs[k].start_s,
            from_controller=all_runs[k - 1].controller,
            to_controller=all_runs[k].controller,
            reasons=definitions.bit_names(int(mask), log.reason_names),
            duration_s=all_runs[k].end_s - all_runs[k].start_s,
            until_end=(k == len(all_runs) - 1),
            stable_for_s=float(d.stable_for_s[i])))
    return out


def _name(log, value):
    return log.controller_names.get(int(value), "controller %d" % int(value))
