#!/usr/bin/env python3
"""make bench-hil: the whole HiL stack in lockstep (every HP node, the HA SIL, the simulator) as
a multiple of real time at 100 Hz and at 20 Hz (HA and controller both at the rate), and where
each step's wall time goes, from the simulator's own phase timers:

  scenario        crash injection check, progress, loop overhead
  sensors         VN-200 packets built and written to both ptys
  wait_hp_inputs  until the vn200 node has published them and the HA's status of the last step is out
  wait_controller /clock published until the controller's /servo_op came back (its periods only)
  ha_step         the HA: command taken from the arduino node over the link, one core period, reply
  truth           /hil/truth built and published
  fdm             JSBSim advanced by one period (2 steps of 5 ms at 100 Hz)
  restart         time held while the supervisor restarted the controller
and the simulator's own CPU time per step (its process, rospy's threads included): its share of
the work, which on a loaded machine the wall time hides.

One flight per rate, SECONDS of simulated time with the HP crash at a third of it and no bag.
Then one flight of REALTIME_SECONDS in real time (no crash) for the latency through the whole
chain: a VN-200 packet written to the HP's pty, the vn200 node, the controller (stepping on the
packet), the arduino node, the HA's link and the period the command's arrival runs driving the
servos with it (hil/README.md, "Sensor to servo").
Then a seeded fault campaign of 150 flights over every fault class on Dask (bench_campaign.py:
the Simplex property over all of them, flights per hour, the campaign's speed).
Wall time on a shared machine measures the neighbours too. Prints `metric: value unit` lines,
then `machine: ...`."""
import argparse
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
from bench_fdm import machine  # noqa: E402
import bench_campaign  # noqa: E402

SECONDS = 60
REALTIME_SECONDS = 30


def flight(aircraft, rate_hz, realtime=False):
    d = tempfile.mkdtemp(prefix="bench_hil_")
    folder = os.path.join(d, "flight")
    args = ["--duration", str(REALTIME_SECONDS), "--crash-at", "-1", "--realtime"] if realtime else \
        ["--duration", str(SECONDS), "--crash-at", str(SECONDS // 3)]
    r = subprocess.run([sys.executable, os.path.join(HERE, "..", "run_flight.py"), "--quiet", "--no-bag",
                        "--aircraft", aircraft, "--rate-hz", str(rate_hz), "--controller-hz", str(rate_hz),
                        "--folder", folder] + args,
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    if r.returncode != 0:
        sys.stdout.write(r.stdout.decode(errors="replace")[-2000:])
        raise SystemExit("bench-hil: the %g Hz flight failed" % rate_hz)
    with open(os.path.join(folder, "summary.json")) as f:
        return json.load(f)


def main():
    ap = argparse.ArgumentParser(description="the HiL stack's speed, latency and campaign throughput")
    ap.add_argument("--aircraft", default="DG808", help="the build's (make bench-hil AIRCRAFT=<name>)")
    aircraft = ap.parse_args().aircraft
    header = machine()
    sys.stderr.write("bench-hil: aircraft %s\n" % aircraft)
    for rate in (100, 20):
        s = flight(aircraft, rate)
        steps_per_s = s["x_real_time"] * rate
        print("hil_lockstep_speed_%dhz: %.2f x_realtime" % (rate, s["x_real_time"]))
        print("hil_lockstep_steps_%dhz: %.0f steps/s" % (rate, steps_per_s))
        print("hil_sim_cpu_per_step_%dhz: %.3f ms" % (rate, s["sim_cpu_ms_per_step"]))
        total = sum(s["step_time_ms"].values())
        for phase, ms in sorted(s["step_time_ms"].items(), key=lambda kv: -kv[1]):
            print("hil_step_%dhz_%s: %.3f ms (%.0f %%)" % (rate, phase, ms, 100.0 * ms / total if total else 0.0))
    lat = flight(aircraft, 100, realtime=True)["sensor_to_servo_latency"]
    print("hil_sensor_to_servo_latency_p50: %.2f ms" % lat["p50_ms"])
    print("hil_sensor_to_servo_latency_p99: %.2f ms" % lat["p99_ms"])
    print("hil_sensor_to_servo_latency_max: %.2f ms (%d packets, real time, 100 Hz)" % (lat["max_ms"], lat["packets"]))
    sys.stdout.flush()
    for name, value in bench_campaign.run(aircraft):
        print("hil_campaign_%s: %s" % (name, value))
    print("machine: %s" % header)


if __name__ == "__main__":
    main()
