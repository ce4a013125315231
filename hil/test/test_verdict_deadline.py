"""The verdict judges a crash's takeover on the HA's own periods (hil/verdicts.py): the deadline
is missed at the end of the (late_periods_tolerated + 1)-th HA period in a row without a new
command, and the HA must fly within one HA period of that. In lockstep that is the crash's step
plus the tolerated periods; in real time the HP's timer, the kill and the HA's ticks run at any
phase to each other, and the simulator sees a tick only at its next step. Synthetic timelines,
the first from the flight of issue 24 (hil/README.md, "Deadline semantics")."""
import os
from collections import namedtuple

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
from hil import verdicts  # noqa: E402
from hil.flight_record import Period  # noqa: E402
from hil.faults.crash import Crash  # noqa: E402

PERIOD_S = 0.01
Regions = namedtuple("Regions", "period_s late_periods_tolerated")
REGIONS = Regions(PERIOD_S, 1)
DEADLINE_MISS = 2
PACE0_MONO = 230.4156  # time.monotonic() of simulated 0: the crash step (30.00 s) ran at 260.4156


def realtime_periods(ha_phase_s, commands_at_s, switch_after_deadline=0, t0=29.9, t1=30.2):
    """The HA's ticks on its own clock (monotonic seconds, as the simulator keeps them) from
    simulated t0 to t1, every PERIOD_S at ha_phase_s past the simulator's step; each with the
    commands its link had delivered by then, the controller (the HA from the deadline-miss
    tick plus switch_after_deadline ticks on) and the reasons at the switch."""
    ticks = [round(t0 + ha_phase_s + i * PERIOD_S, 6) for i in range(int(round((t1 - t0) / PERIOD_S)))]
    counts = [sum(1 for c in commands_at_s if c <= t) for t in ticks]
    late, deadline = 0, None
    for i in range(1, len(ticks)):
        late = late + 1 if counts[i] == counts[i - 1] else 0
        if late > REGIONS.late_periods_tolerated and deadline is None:
            deadline = i
    switch = len(ticks) if deadline is None or switch_after_deadline is None else deadline + switch_after_deadline
    return [(PACE0_MONO + t, n, 1 if i >= switch else 0, DEADLINE_MISS if i >= switch else 0)
            for i, (t, n) in enumerate(zip(ticks, counts))]


class RealtimeSim:
    def __init__(self, periods, crashed_at=30.0):
        self.ha_periods = periods
        self.pace0_mono = PACE0_MONO
        self.regions = REGIONS
        self.crashed_at = crashed_at


def hp_commands(phase_s, last_s):
    """The HP's timer: a command arriving every period at phase_s, the last at or before last_s."""
    n = int((last_s - 29.5 - phase_s) / PERIOD_S + 1e-6)
    return [round(29.5 + phase_s + i * PERIOD_S, 6) for i in range(n + 1)]


def test_the_real_time_crash_of_issue_24_is_taken_over_at_the_has_own_deadline_miss():
    # The flight's bag: the HP's commands reach the HA 6 ms before the crash step, the HA ticks
    # 0.2 ms after the simulator's step; the last command (29.994) is taken at the HA's tick of
    # 30.0002, none in the periods ending 30.0102 and 30.0202: missed then, and the HA flies then.
    # The simulator first saw it at its step of 30.03, and the old rule put the deadline at
    # crash + 1 period = 30.01: "0.02 s after the deadline miss".
    sim = RealtimeSim(realtime_periods(0.0002, hp_commands(0.0041, 29.9941)))
    tk = verdicts.crash_takeover(verdicts.ha_periods(sim), 30.0, REGIONS)
    assert tk["first_missed_period_s"] == 30.01 and tk["deadline_miss_s"] == 30.02, tk
    assert tk["takeover_s"] == 30.02 and tk["latency_after_deadline_miss_s"] == 0.0, tk
    assert tk["within_one_period_of_deadline_miss"] and tk["reasons_at_switch"] == DEADLINE_MISS, tk


def test_the_deadline_lies_up_to_two_periods_further_on_when_the_last_command_just_missed_a_tick():
    # The last command arrives 0.1 ms after an HA tick and just before the kill: that tick did not
    # see it, the next one (30.0099) does, and only the periods after it can be late.
    sim = RealtimeSim(realtime_periods(-0.0001, hp_commands(0.0, 30.0)))
    tk = verdicts.crash_takeover(verdicts.ha_periods(sim), 30.0, REGIONS)
    assert tk["deadline_miss_s"] == 30.03 and tk["takeover_s"] == 30.03, tk
    assert tk["within_one_period_of_deadline_miss"], tk


def test_a_takeover_one_period_after_the_deadline_miss_passes_and_two_periods_after_is_rejected():
    commands = hp_commands(0.0041, 29.9941)
    one = verdicts.crash_takeover(verdicts.ha_periods(RealtimeSim(realtime_periods(0.0002, commands, 1))), 30.0, REGIONS)
    assert one["deadline_miss_s"] == 30.02 and one["takeover_s"] == 30.03, one
    assert one["latency_after_deadline_miss_s"] == 0.01 and one["within_one_period_of_deadline_miss"], one
    two = verdicts.crash_takeover(verdicts.ha_periods(RealtimeSim(realtime_periods(0.0002, commands, 2))), 30.0, REGIONS)
    assert two["takeover_s"] == 30.04 and two["latency_after_deadline_miss_s"] == 0.02, two
    assert not two["within_one_period_of_deadline_miss"], two
    never = verdicts.crash_takeover(verdicts.ha_periods(RealtimeSim(realtime_periods(0.0002, commands, None))), 30.0, REGIONS)
    assert never["takeover_s"] is None and not never["within_one_period_of_deadline_miss"], never


def test_the_crash_faults_due_time_is_the_has_deadline_miss_in_real_time():
    # What fault_verdict judges the takeover against (Crash.takeover_due_s): the HA's tick, not
    # crash + late_periods_tolerated periods.
    crash = Crash(RealtimeSim(realtime_periods(0.0002, hp_commands(0.0041, 29.9941))), 30.0, -1.0, {})
    crash.confirmed = True
    assert round(crash.takeover_due_s(), 6) == 30.0202  # the tick closing the second late period
    late = Crash(RealtimeSim(realtime_periods(-0.0001, hp_commands(0.0, 30.0))), 30.0, -1.0, {})
    late.confirmed = True
    assert round(late.takeover_due_s(), 6) == 30.0299


Reply = namedtuple("Reply", "commands_received controller reasons_at_switch")


def test_in_lockstep_the_crashs_own_step_is_the_first_late_period():
    # One HA period per simulator step; the controller killed at step 30.00 sends nothing in it.
    steps = [round(29.9 + i * PERIOD_S, 6) for i in range(20)]
    records = [Period(int(round(t * 1e6)), None, Reply(sum(1 for c in steps if c < 30.0 - 1e-9 and c <= t),
                                                  1 if t >= 30.01 - 1e-9 else 0, DEADLINE_MISS), None, 60.0)
               for t in steps]

    class LockstepSim:
        pass
    sim = LockstepSim()
    sim.records = records
    tk = verdicts.crash_takeover(verdicts.ha_periods(sim), 30.0, REGIONS)
    assert (tk["first_missed_period_s"], tk["deadline_miss_s"], tk["takeover_s"]) == (30.0, 30.01, 30.01), tk
    assert tk["latency_after_deadline_miss_s"] == 0.0 and tk["within_one_period_of_deadline_miss"], tk


def test_one_late_period_of_jitter_before_the_crash_is_not_the_deadline_miss():
    # 29.95: the HP's command slips past the HA's tick (none in that period, two in the next):
    # tolerated, and not a deadline miss; the crash's comes after it.
    commands = [c for c in hp_commands(0.0041, 29.9941) if abs(c - 29.9441) > 1e-6] + [29.9503]
    periods = verdicts.ha_periods(RealtimeSim(realtime_periods(0.0002, sorted(commands))))
    late = [round(periods[i].t_s, 6) for i in range(1, len(periods))
            if periods[i].commands_received == periods[i - 1].commands_received]
    assert late[:3] == [29.9502, 30.0102, 30.0202], late  # the jitter's one, then the crash's
    assert tuple(round(t, 6) for t in verdicts.command_deadline(periods, 29.9, 1)) == (30.0102, 30.0202)


def test_the_has_ticks_are_dated_on_its_own_wrapping_32_bit_microsecond_clock():
    from hil.sim import Simulation
    R = namedtuple("R", "t_us commands_received controller reasons_at_switch")

    class Sim:  # what note_ha_periods touches of a Simulation: its list of dated HA periods
        ha_periods = []
    now = 5000.25  # s: past 2^32 us, so the HA's micros() has wrapped
    now_us = int(now * 1e6)
    Simulation.note_ha_periods(Sim, [R((now_us - 2500) & 0xFFFFFFFF, 7, 0, 0),
                                      R((now_us + 3) & 0xFFFFFFFF, 8, 1, DEADLINE_MISS)], now)
    (t_a, n_a, c_a, _), (t_b, n_b, c_b, why) = Sim.ha_periods
    assert round(now - t_a, 6) == 0.0025 and (n_a, c_a) == (7, 0)
    assert round(t_b - now, 6) == 0.000003 and (n_b, c_b, why) == (8, 1, DEADLINE_MISS)


def test_who_had_the_servos_before_the_crash_is_read_on_the_has_ticks():
    # The HP kept its deadline up to the kill: the HP, whatever the simulator's late steps showed.
    on_time = verdicts.crash_takeover(verdicts.ha_periods(RealtimeSim(realtime_periods(0.0002, hp_commands(0.0041, 29.9941)))), 30.0, REGIONS)
    assert on_time["controller_before_crash"] == "HP", on_time
    # The HP fell silent 50 ms before the kill (late on a loaded machine): the HA already flew,
    # and this flight's takeover says nothing of the crash's.
    late = verdicts.crash_takeover(verdicts.ha_periods(RealtimeSim(realtime_periods(0.0002, hp_commands(0.0041, 29.9441)))), 30.0, REGIONS)
    assert late["controller_before_crash"] == "HA", late
