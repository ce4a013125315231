"""Who flew when, computed once (report_core.switches.stretches) and read by name from the
simulator's periods (hil.flight_record): the HiL's verdict and the flight report cut the same
controller series at the same samples."""
from collections import namedtuple
from types import SimpleNamespace

from drone_ros.msg import DecisionStatus
from report_core import switches
from report_core.switches import Stretch, stretches

from hil import verdicts
from hil.flight_record import Period

HP, HA, REC = DecisionStatus.CONTROLLER_HP, DecisionStatus.CONTROLLER_HA, DecisionStatus.CONTROLLER_RECOVERING
Reply = namedtuple("Reply", "controller reasons_at_switch reasons stable_for_s")
SERIES = [HA, HA, REC, HP, HP, HP, HA, REC, REC, HP]


def test_a_series_is_cut_where_the_controller_changes_and_nowhere_else():
    assert stretches(SERIES) == [Stretch(HA, 0, 2), Stretch(REC, 2, 3), Stretch(HP, 3, 6),
                                 Stretch(HA, 6, 7), Stretch(REC, 7, 9), Stretch(HP, 9, 10)]
    assert stretches([HP] * 4) == [Stretch(HP, 0, 4)]
    assert stretches([]) == []


def test_the_verdicts_who_flew_and_the_reports_runs_agree_on_one_flight():
    periods = [Period(i * 10000, None, Reply(c, DecisionStatus.REASON_DEADLINE_MISS if c == HA else 0, 0, 0.5), None, 60.0)
               for i, c in enumerate(SERIES)]
    who_flew = verdicts.segments(periods)
    log = SimpleNamespace(decision=SimpleNamespace(t=[p.t_s for p in periods], controller=SERIES),
                          controller_names=dict(verdicts.CONTROLLERS))
    runs = switches.runs(log)
    assert [(s["controller"], s["from_s"], s["to_s"]) for s in who_flew] == \
        [(r.controller, round(r.start_s, 3), round(r.end_s, 3)) for r in runs]
    assert [s["controller"] for s in who_flew] == ["HA", "RECOVERING", "HP", "HA", "RECOVERING", "HP"]
    assert who_flew[3]["why"] == ["DEADLINE_MISS"] and who_flew[2]["why"] == []
    assert (who_flew[-1]["from_s"], who_flew[-1]["to_s"]) == (0.09, 0.09)  # the last period ends the log


def test_a_period_is_read_by_name_and_still_unpacks_as_before():
    p = Period(1500000, "truth", "reply", 7, 61.5)
    assert (p.t_s, p.truth, p.reply, p.cmd_seq, p.airspeed_cal_ftps) == (1.5, "truth", "reply", 7, 61.5)
    t_us, _, _, _, cal = p
    assert (t_us, cal) == (1500000, 61.5)
