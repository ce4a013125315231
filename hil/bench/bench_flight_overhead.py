#!/usr/bin/env python3
"""make bench-flight-overhead: what one lockstep flight costs besides its steps, phase by phase.

Every flight of the test suite (some 75 of them in make test) pays it: run_flight.py's start and
the master, roslaunch starting every node, the simulator's start-up (rospy, its model of the
aircraft, ptys), the preflight (until every node is connected), the verdict and summary, and the
teardown. The flights are the shortest that still fly (SIM_S of simulated time: 2 s parked, the
mission upload, the airborne start), no fault, no bag; the figures are the median of RUNS flights,
from run_flight_times.json and sim_times.json (wall-clock marks both write in the flight's
folder), plus the CPU time of the flight's whole process tree and its split by process: each
process of the flight (found by a token in its environment, which every process the flight starts
inherits) is read from /proc every 20 ms, and its last reading counts, so the CPU of a process's
last 20 ms is missed (a lower bound, short by a few ms a process). Wall time on a shared machine
measures the neighbours too. Prints `metric: value unit` lines, then `machine: ...`."""
import collections
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
import uuid

HERE = os.path.dirname(os.path.abspath(__file__))
from stack_tools.bench_machine import machine  # noqa: E402
from hil import proc_stat  # noqa: E402
from hil.campaigns import flight as flight_mod  # noqa: E402  (a flight's processes, by its token)

RUNS = int(os.environ.get("BENCH_FLIGHT_RUNS", "3"))
SIM_S = 3.0
# (metric, from mark, to mark): consecutive, so the phases add up to the whole flight.
PHASES = [("run_flight_start_to_master_up", "start", "master_up"),
          ("roslaunch_to_simulator_process", "launch_started", "sim_started"),
          ("simulator_imports", "sim_started", "sim_imported"),
          ("simulator_node_registration", "sim_imported", "node_up"),
          ("simulator_set_up", "node_up", "sim_set_up"),
          ("preflight_until_every_node_connected", "sim_set_up", "preflight_done"),
          ("flight_steps_incl_mission_upload", "preflight_done", "flight_done"),
          ("verdict_and_summary", "flight_done", "summary_written"),
          ("done_seen_by_run_flight", "summary_written", "done_seen"),
          ("teardown", "done_seen", "stopped"),
          ("run_flight_exit", "stopped", "end")]


def process_name(pid):
    """What a process of the flight is: its ROS node name (__name:=), else its program (the
    script, for an interpreter)."""
    try:
        with open("/proc/%d/cmdline" % pid, "rb") as f:
            argv = [a.decode(errors="replace") for a in f.read().split(b"\0") if a]
    except OSError:
        return None
    for a in argv:
        if a.startswith("__name:="):
            return a[len("__name:="):]
    prog = [os.path.basename(a) for a in argv[:2]]
    return prog[1] if prog and prog[0].startswith("python") and len(prog) > 1 else (prog[0] if prog else None)


class ProcessCpu:
    """CPU seconds of every process holding the flight's token (hil.campaigns.flight's), by
    name, as last read from /proc."""

    def __init__(self, token):
        self.token = token
        self.last = {}     # pid -> (name, cpu s)
        self.skip = set()  # pids read without the token
        self.tick = os.sysconf("SC_CLK_TCK")

    def poll(self):
        for pid in flight_mod.holders(self.token, self.skip):
            fields = proc_stat.stat_fields(pid)
            if fields is not None:  # utime, stime: fields 14 and 15 of stat(5)
                name = self.last[pid][0] if pid in self.last else process_name(pid)
                self.last[pid] = (name, (int(fields[11]) + int(fields[12])) / self.tick)

    def by_name(self):
        out = collections.defaultdict(float)
        for name, cpu in self.last.values():
            out[name or "?"] += cpu
        return dict(out)


def fly():
    folder = os.path.join(tempfile.mkdtemp(prefix="bench_overhead_"), "flight")
    cpu0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    token = uuid.uuid4().hex
    procs = ProcessCpu(token)
    log = tempfile.TemporaryFile()  # not a pipe: polling /proc, this would not drain one
    t0 = time.time()
    p = subprocess.Popen([sys.executable, os.path.join(HERE, "..", "run_flight.py"), "--quiet", "--no-bag",
                          "--fault", "none", "--duration", "%g" % SIM_S, "--folder", folder],
                         env=dict(os.environ, **{flight_mod.TOKEN_VAR: token}), stdout=log, stderr=subprocess.STDOUT)
    while p.poll() is None:
        procs.poll()
        time.sleep(0.02)
    end = time.time()
    log.seek(0)
    output = log.read()
    log.close()
    cpu1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    if p.returncode != 0:
        sys.stdout.write(output.decode(errors="replace")[-2000:])
        raise SystemExit("bench-flight-overhead: the flight failed")
    marks = {}
    for name in ("run_flight_times.json", "sim_times.json"):
        with open(os.path.join(folder, name)) as f:
            marks.update(json.load(f))
    marks["end"] = end
    # The launch starts once the master is up; from the process's start to that is run_flight's.
    marks["launch_started"] = marks.get("launch_started", marks["master_up"])
    phases = {name: marks[b] - marks[a] for name, a, b in PHASES}
    phases["whole_flight"] = end - t0
    cpu = (cpu1.ru_utime - cpu0.ru_utime) + (cpu1.ru_stime - cpu0.ru_stime)
    return phases, cpu, procs.by_name()


def main():
    header = machine("%d flights of %g s simulated, lockstep 100 Hz, no bag" % (RUNS, SIM_S))
    runs = [fly() for _ in range(RUNS)]
    for name in [p[0] for p in PHASES] + ["whole_flight"]:
        print("flight_overhead_%s: %.2f s" % (name, statistics.median(r[0][name] for r in runs)))
    print("flight_overhead_cpu_whole_flight: %.2f s (every process of the flight)" %
          statistics.median(r[1] for r in runs))
    by_name = {n: statistics.median(r[2].get(n, 0.0) for r in runs) for n in set().union(*(r[2] for r in runs))}
    for name, cpu in sorted(by_name.items(), key=lambda kv: -kv[1]):
        print("flight_overhead_cpu_%s: %.2f s" % (name.replace(".", "_").replace("-", "_"), cpu))
    print("machine: %s" % header)


if __name__ == "__main__":
    main()
