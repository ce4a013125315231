"""The VN-200's noise (hil/sensors.py) is a function of the seed alone: the navigation filter's
Gauss-Markov errors, drawn nine at a time per 800 Hz grid step in C (hil/native/ins_noise.c), are
the very numbers that one random.Random.gauss call per draw gives, whatever the batch sizes; a
seeded flight flies as it did when Python drew them (test_determinism holds a flight to itself)."""
import math
import random

import pytest

from hil import ins_noise, sensors


def test_the_c_draws_the_gauss_calls_normals_draw_for_draw_and_hands_the_generator_back():
    for sizes in ([1], [2], [9], [72, 9, 1, 3, 0, 8], [5, 5, 5, 5, 5, 5, 5], [1400]):
        one_by_one, handed = random.Random("7/x"), random.Random("7/x")
        one_by_one.gauss(0.0, 1.0)  # a pair cached: the C starts with its second value
        handed.gauss(0.0, 1.0)
        noise = ins_noise.InsNoise(handed, [0.0] * 9, [0.0] * 9, [0.0] * 9)
        for n in sizes:
            want = [one_by_one.gauss(0.0, 1.0) for _ in range(n)]
            got = noise.normals(n)
            assert [x.hex() for x in got] == [x.hex() for x in want], sizes
        # Whatever the C left kept, the generator handed back goes on as the other does (1,400
        # normals regenerate the twister's 624 words more than once).
        back = random.Random()
        back.setstate(noise.random_state())
        assert back.gauss(0.0, 1.0).hex() == one_by_one.gauss(0.0, 1.0).hex()
        assert back.random() == one_by_one.random()


def test_a_state_random_does_not_give_is_refused():
    version, words, cached = random.Random(3).getstate()
    with pytest.raises(ValueError, match="not a random.Random state"):
        ins_noise.InsNoise(_State(version, words[:624] + (625,), cached), [0.0] * 9, [0.0] * 9, [0.0] * 9)


def test_a_grid_index_not_drawn_or_no_longer_kept_is_refused():
    noise = ins_noise.InsNoise(random.Random(5), [0.5] * 9, [1.0] * 9, [0.0] * 9)
    noise.start(100)
    noise.draw_to(100 + noise.keep)
    assert len(noise.at(100 + noise.keep)) == 9 and len(noise.at(101)) == 9
    for index in (100, 101 + noise.keep):
        with pytest.raises(IndexError, match="not among the last"):
            noise.at(index)


class _State:
    """Something whose getstate() is a given state."""

    def __init__(self, *state):
        self.state = state

    def getstate(self):
        return self.state


def per_draw_errors(seed, times_s):
    """The filter's errors as one GaussMarkov.step per process and grid step gives them."""
    r = random.Random("%s/ins_solution" % seed)
    procs = ([sensors.GaussMarkov(r, s, 20.0) for s in (0.2, 0.03, 0.03)] +
             [sensors.GaussMarkov(r, s, 60.0) for s in (1.0 / math.sqrt(2.0), 1.0 / math.sqrt(2.0), 1.5)] +
             [sensors.GaussMarkov(r, 0.05, 5.0) for _ in range(3)])
    index, x, out = None, None, []
    for t in times_s:
        k = int(math.floor(t * 800.0 + 1e-6))
        if index is None:
            index, x = k, [p.x for p in procs]
        while index < k:
            index += 1
            x = [p.step(1.0 / 800.0) for p in procs]
        out.append((x[0:3], x[3:6], x[6:9]))
    return out


def test_the_filter_errors_at_packet_times_are_the_per_draw_process_to_the_bit():
    # Both ports' packets: 100 Hz and 200 Hz sensor times, a packet now and then a grid step
    # late, and a gap of a lost second.
    times = sorted([i * 0.01 for i in range(400)] + [i * 0.005 + 0.00125 for i in range(800)] +
                   [5.0 + i * 0.01 for i in range(100)])
    for seed in (1, 11, 26):
        errors = sensors.InsSolutionErrors(seed)
        got = [errors.at(t) for t in times]
        assert [[[v.hex() for v in part] for part in e] for e in got] == \
            [[[v.hex() for v in part] for part in e] for e in per_draw_errors(seed, times)], seed


def test_errors_drawn_ahead_while_the_controller_computes_are_the_ones_drawn_on_demand():
    # The simulator draws the next step's grid while it waits for the controller: the packets
    # then read what they would have drawn themselves, whatever came ahead or not at all.
    times = [i * 0.01 for i in range(300)]
    for seed in (1, 11, 26):
        ahead = sensors.InsSolutionErrors(seed)
        ahead.draw_until(0.5)  # before the first packet: the first packet fixes the grid
        got = []
        for t in times:
            got.append(ahead.at(t))
            if int(round(t * 100)) % 3:  # not every step waits for a controller
                ahead.draw_until(t + 0.01)
        want = per_draw_errors(seed, times)
        assert [[[v.hex() for v in part] for part in e] for e in got] == \
            [[[v.hex() for v in part] for part in e] for e in want], seed
