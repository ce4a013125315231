"""What the figures draw of a long log: thinned to the figure's resolution without losing a spike,
and broken where messages stopped."""

import numpy as np


from report_core import figures  # noqa: E402


def test_an_hour_at_100hz_is_thinned_keeping_every_spike_and_the_ends():
    t = np.arange(360000) / 100.0
    y = np.sin(t / 60.0)
    y[123457] = 50.0    # one period's glitch
    y[300001] = -50.0
    t2, y2 = figures._thin(t, y, max_points=8000)
    assert len(t2) <= 8000 + 2 * (len(t) // 4000)
    assert np.all(np.diff(t2) > 0)
    assert 50.0 in y2 and -50.0 in y2
    assert t2[-1] == t[-1]
    assert y2.max() == y.max() and y2.min() == y.min()


def test_a_short_series_is_drawn_as_it_is():
    t, y = np.arange(10.0), np.arange(10.0) ** 2
    t2, y2 = figures._thin(t, y)
    assert np.array_equal(t2, t) and np.array_equal(y2, y)


def test_a_stretch_without_messages_is_not_bridged_by_the_line():
    t = np.concatenate((np.arange(0, 30, 0.01), np.arange(45, 60, 0.01)))
    t2, y2 = figures._broken(t, np.ones_like(t))
    gap = np.flatnonzero(np.isnan(y2))
    assert len(gap) == 1 and t2[gap[0] - 1] < 30.0 < 45.0 <= t2[gap[0] + 1]


def test_a_restarted_hps_commands_are_not_aged_against_its_predecessors():
    """At 100 Hz the HP crashes at 100 s and its successor counts from 0 again; the HA's decisions
    come stamped 5 ms before the command they judged (rosserial time sync in lockstep)."""
    class Series:
        def __init__(self, **columns):
            self.__dict__.update(columns)

    first = np.arange(0, 10000)
    second = np.arange(0, 2000)
    op_stamp = np.concatenate((first / 100.0, 100.02 + second / 100.0))
    op_seq = np.concatenate((first, second)).astype(float)
    log = Series(servo_op=Series(t=op_stamp, seq=op_seq, stamp=op_stamp),
                 decision=Series(t=op_stamp - 0.005, last_seq=op_seq, stamp=op_stamp - 0.005))
    t, age = figures.command_age_s(log, lead_s=0.01)
    assert len(t) == len(op_stamp)
    assert np.all(np.abs(age) < 0.01), age[np.abs(age) >= 0.01][:5]
