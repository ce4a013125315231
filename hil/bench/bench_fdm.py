#!/usr/bin/env python3
"""make bench-fdm: how many times real time the flight-dynamics model runs.

The loop a lockstep HiL runs: dt 1/200 s, light turbulence, and at 100 Hz new surface commands
in and a Truth out. Each run flies 60 s of simulated time from a trimmed start; the figure is the
median of RUNS runs. Times are the process's CPU time (the machine is shared, so wall time
mostly measures the neighbours); the wall-clock figure is printed alongside.
Prints `metric: value unit` lines, then `machine: ...`.
"""
import dataclasses
import math
import os
import statistics
import sys
import time

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
from stack_tools.bench_machine import machine  # noqa: E402
from hil.fdm import Fdm, Wind  # noqa: E402

AIRCRAFT = os.path.join(ROOT, "aircraft", "DG808")
RUNS = 5
SIM_S = 60.0
CONTROL_HZ = 100


def one_run(fdm, with_io):
    trim = fdm.reset_airborne(47.4, 8.5, 420.0, 100.0, 0.0, 18.0)
    period = 1.0 / CONTROL_HZ
    n = int(round(SIM_S * CONTROL_HZ))
    cpu0, wall0 = time.process_time(), time.perf_counter()
    for k in range(n):
        if with_io:
            fdm.set_surfaces(dataclasses.replace(trim, aileron_deg=3.0 * math.sin(0.5 * k * period)))
        fdm.advance(period)
        if with_io:
            fdm.truth()
    return SIM_S / (time.process_time() - cpu0), SIM_S / (time.perf_counter() - wall0)


def trim_ms(fdm):
    cpu0 = time.process_time()
    fdm.reset_airborne(47.4, 8.5, 420.0, 100.0, 0.0, 18.0)
    return 1000.0 * (time.process_time() - cpu0)


def main():
    header = machine()
    with Fdm(AIRCRAFT, seed=1, dt_s=1.0 / 200.0, wind=Wind(270.0, 5.0, "light")) as fdm:
        full = [one_run(fdm, True) for _ in range(RUNS)]
        bare = [one_run(fdm, False) for _ in range(RUNS)]
        trims = [trim_ms(fdm) for _ in range(RUNS)]
    print("fdm_speed: %.0f x_realtime" % statistics.median(x[0] for x in full))
    print("fdm_speed_wall: %.0f x_realtime" % statistics.median(x[1] for x in full))
    print("fdm_speed_advance_only: %.0f x_realtime" % statistics.median(x[0] for x in bare))
    print("fdm_step_cost: %.1f us" % (1e6 / 200.0 / statistics.median(x[0] for x in bare)))
    print("fdm_trim_time: %.1f ms" % statistics.median(trims))
    print("machine: %s" % header)
    return 0


if __name__ == "__main__":
    sys.exit(main())
