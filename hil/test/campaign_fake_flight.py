#!/usr/bin/env python3
"""A stand-in for hil/run_flight.py in the campaign runner's tests: the same command line, and per
fault class one way a flight ends, so the runner's handling of each can be shown quickly:
  quick    writes a summary.json like the lockstep flight's (its verdict and fault record as
           hil.verdicts writes them) and exits 0
  unjudged the same without the verdict: a summary an older run_flight.py wrote
  wait     the same once the file CAMPAIGN_TEST_RELEASE names exists (a flight still flying)
  die      writes error.txt and exits 3, no summary (a flight that died)
  stuck    starts two processes in sessions of their own, as run_flight.py starts roscore and
           roslaunch, one of them ignoring SIGTERM, and never ends (a flight past its limit);
           the pids go to <folder>/pids as they start
--master URI (a worker's kept ROS master) is answered as run_flight.py would use it: the fake
asks the master for its pid and writes what it found to <folder>/master.json."""
import argparse
import json
import os
import signal
import subprocess
import sys
import time

STUCK_CHILD = ("import signal, time\n"
               "signal.signal(signal.SIGTERM, signal.SIG_IGN)\n"
               "while True: time.sleep(1)\n")


def summary(args):
    verdict = {"ok": True, "unsafe_commands": 0, "envelope_violations_under_ha_s": 0.0,
               "envelope_under_ha": {"outside_S_x_s": 0.0, "inherited_from_hp_s": 0.0,
                                     "left_under_ha_s": 0.0, "max_S_x_row": 0.4, "worst": None},
               "takeover_latency_s": 0.01, "takeover_within_one_period": True, "recovery_s": 4.5,
               "latched": False, "aircraft_crashed": False, "min_height_agl_ft": 150.0,
               "min_airspeed_margin_ftps": 12.0, "mission_progress": 0.0938, "stalled_under_ha_s": 0.0,
               "longest_stall_under_ha_s": 0.0, "stalled_from_fault_s": 0.0, "recovery_height_loss_ft": 3.0}
    fault = {"class": args.fault, "at_s": args.fault_at, "duration_s": args.fault_duration, "params": {},
             "took_effect": True, "evidence": "t=%g s: SIGKILL" % args.fault_at, "notes": [], "detail": None}
    return {"seed": args.seed, "simulated_s": args.duration, "wall_s": 1.0, "x_real_time": 1.0,
            "who_flew": [{"controller": "HP"}, {"controller": "HA"}, {"controller": "HP"}],
            "world": {"beyond_design_wind": []},
            "events": [{"t_s": args.fault_at, "event": "HP crash injected: SIGKILL"}],
            "fault": fault, "verdict": verdict, "status": "ok"}


def main():
    ap = argparse.ArgumentParser()
    for flag in ("--seed",):
        ap.add_argument(flag, type=int)
    for flag in ("--fault-at", "--fault-duration", "--duration"):
        ap.add_argument(flag, type=float)
    ap.add_argument("--fault")
    ap.add_argument("--fault-param", action="append", default=[])
    ap.add_argument("--folder")
    ap.add_argument("--ha", choices=("sil", "qemu"), default="sil")
    ap.add_argument("--aircraft")
    ap.add_argument("--no-bag", action="store_true")
    ap.add_argument("--quiet", action="store_true")
    ap.add_argument("--master", default=None)
    args = ap.parse_args()
    os.makedirs(args.folder, exist_ok=True)
    if args.master:
        import xmlrpc.client
        code, _, pid = xmlrpc.client.ServerProxy(args.master).getPid("/campaign_fake_flight")
        with open(os.path.join(args.folder, "master.json"), "w") as f:
            json.dump({"uri": args.master, "code": code, "pid": pid}, f)
    if args.fault == "die":
        with open(os.path.join(args.folder, "error.txt"), "w") as f:
            f.write("the simulator stopped: test death\n")
        return 3
    if args.fault == "stuck":
        signal.signal(signal.SIGTERM, signal.SIG_IGN)
        with open(os.path.join(args.folder, "pids"), "w") as f:
            for _ in range(2):
                p = subprocess.Popen([sys.executable, "-c", STUCK_CHILD], start_new_session=True)
                f.write("%d\n" % p.pid)
                f.flush()
        while True:
            time.sleep(1)
    if args.fault == "wait":
        while not os.path.exists(os.environ["CAMPAIGN_TEST_RELEASE"]):
            time.sleep(0.05)
    written = summary(args)
    if args.fault == "unjudged":
        del written["verdict"]
    with open(os.path.join(args.folder, "summary.json"), "w") as f:
        json.dump(written, f)
    return 0


if __name__ == "__main__":
    sys.exit(main())
