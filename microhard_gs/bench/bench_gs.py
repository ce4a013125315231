#!/usr/bin/env python3
"""make bench-gs: does microhard_gs hold its telemetry rate, and what CPU share does it take?

For each rate, starts the node (own ROS master, UDP on 127.0.0.1), feeds /data at 50 Hz from the
probe, counts the ATTITUDE messages a pymavlink client receives over a measured window and reads
the node's CPU time from /proc. Prints `metric: value unit` lines, then `machine: ...`.
"""
import os
import sys
import time

from stack_testing import gs_harness as gh  # noqa: E402
from stack_tools.bench_machine import machine  # noqa: E402

WINDOW_S = 10.0
CLK_TCK = os.sysconf("SC_CLK_TCK")


def children(pid):
    out = []
    try:
        for tid in os.listdir("/proc/%d/task" % pid):
            with open("/proc/%d/task/%s/children" % (pid, tid)) as f:
                out += [int(c) for c in f.read().split()]
    except OSError:
        pass
    return out


def node_pid(launch_pid):
    for pid in children(launch_pid):
        try:
            with open("/proc/%d/cmdline" % pid, "rb") as f:
                if b"__name:=microhard_gs" in f.read():
                    return pid
        except OSError:
            continue
    return None


def cpu_s(pid):
    with open("/proc/%d/stat" % pid) as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / CLK_TCK  # utime + stime


def measure(rate_hz):
    gs = gh.GsSystem(launch_args={"telemetry_rate_hz": float(rate_hz)}, probe_rate_hz=50.0)
    try:
        pid = node_pid(gs.launch.pid)
        if pid is None:
            raise RuntimeError("microhard_gs process not found under roslaunch")
        time.sleep(2.0)  # settle
        while gs.conn.recv_match(blocking=False) is not None:
            pass
        count = 0
        cpu0, t0 = cpu_s(pid), time.monotonic()
        while time.monotonic() - t0 < WINDOW_S:
            m = gs.conn.recv_match(type="ATTITUDE", blocking=True, timeout=0.5)
            if m is not None:
                count += 1
        wall = time.monotonic() - t0
        cpu = cpu_s(pid) - cpu0
        return count / wall, 100.0 * cpu / wall
    finally:
        gs.stop()


def main():
    header = machine()
    for rate in (10, 50):
        achieved, cpu = measure(rate)
        print("gs_telemetry_rate_at_%dhz: %.2f Hz" % (rate, achieved))
        print("gs_telemetry_rate_held_at_%dhz: %.1f %%" % (rate, 100.0 * achieved / rate))
        print("gs_node_cpu_at_%dhz: %.2f %%" % (rate, cpu))
        sys.stdout.flush()
    print("machine: %s" % header)
    return 0


if __name__ == "__main__":
    sys.exit(main())
