"""Who flew when: the runs of one controller and the switches between them, from the HA's
DecisionStatus stream (the HA's own record of its decisions). `stretches` is the one
computation of who flew when: the report's runs here and the HiL's verdicts (hil.verdicts'
`who_flew`, over the simulator's periods) both take it."""
from dataclasses import dataclass, field
from typing import List, NamedTuple, Sequence

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


class Stretch(NamedTuple):
    controller: int
    first: int  # index of its first sample
    end: int  # index past its last sample: the next stretch's first, or the series' length


def stretches(controllers: Sequence[int]):
    """The runs of one controller in a series of samples, in order: [Stretch]. Empty for an
    empty series."""
    out = []
    for i, c in enumerate(controllers):
        c = int(c)
        if not out or out[-1].controller != c:
            if out:
                out[-1] = out[-1]._replace(end=i)
            out.append(Stretch(c, i, len(controllers)))
    return out


def runs(log, cuts=None):
    """[Run], from `cuts` (stretches of the log's controller series) when the caller has them."""
    t = log.decision.t
    cuts = stretches(log.decision.controller) if cuts is None else cuts
    return [Run(_name(log, s.controller), float(t[s.first]), float(t[s.end] if s.end < len(t) else t[-1]))
            for s in cuts]


def switches(log):
    """Every change of the controller in force. A switch to an HA mode carries the checks that
    caused it (reasons_at_switch); any other switch carries the checks failing in that period."""
    d = log.decision
    cuts = stretches(d.controller)
    all_runs = runs(log, cuts)
    index_of_start = [s.first for s in cuts]
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
