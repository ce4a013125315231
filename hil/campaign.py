#!/usr/bin/env python3
"""A seeded fault campaign of lockstep HiL flights on Dask, and its report.

    hil/campaign.py --flights N --seed S [--classes a,b] [--scheduler tcp://HOST:8786] [--out DIR]
                    [--duration S] [--workers N] [--wall-limit S] [--plan-only]
    hil/campaign.py --report DIR          # the report again from DIR/flights.csv

The plan (fault class, time, duration, parameters and seed of every flight) comes from the one
campaign seed; each flight's command line is in the plan, the table and the report, and replays
that flight. Flights run one per Dask task on a LocalCluster (one worker per core, loopback) or on
the scheduler given; each in its own process groups, killed whole past its wall-clock limit. Rows
stream to DIR/flights.csv as flights finish; the report goes to DIR/report/ (report.html,
table.md, report.txt, PNGs). Exits 1 when a flight broke the property, died or ran out of time.
Needs the workspace sourced (the make targets do it)."""
import argparse
import datetime
import os
import sys

from stack_tools.paths import ROOT  # noqa: E402  (aircraft/ of the source tree or the install)
from hil.campaigns import plan as plan_mod  # noqa: E402
from hil.campaigns import report as report_mod  # noqa: E402


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--flights", type=int, default=10)
    ap.add_argument("--aircraft", default="DG808",
                    help="aircraft/<name>/ flown: the build's (make campaign AIRCRAFT=<name> passes it)")
    ap.add_argument("--seed", type=int, default=1, help="the campaign seed")
    ap.add_argument("--classes", default=None, help="comma-separated fault classes (default: every one)")
    ap.add_argument("--scheduler", default=None, help="a Dask scheduler (tcp://HOST:8786); default: a LocalCluster")
    ap.add_argument("--workers", type=int, default=None, help="LocalCluster workers (default: one per core)")
    ap.add_argument("--duration", type=float, default=45.0, help="simulated seconds per flight")
    ap.add_argument("--fault-window", default="8,20", help="the fault starts in this window (s, simulated)")
    ap.add_argument("--ha", choices=("sil", "qemu"), default="sil",
                    help="the HA in every flight: its host build or its Cortex-M3 machine code in QEMU (run_flight.py --ha)")
    ap.add_argument("--wall-limit", type=float, default=None, help="wall-clock seconds a flight may take")
    ap.add_argument("--out", default=None, help="campaign folder (default hil/out/campaign-<date>-<seed>)")
    ap.add_argument("--plan-only", action="store_true", help="print the plan's commands, fly nothing")
    ap.add_argument("--no-progress", action="store_true")
    ap.add_argument("--report", metavar="DIR", default=None, help="only (re)make DIR's report from its flights.csv")
    args = ap.parse_args(argv)

    if args.report:
        _, text = report_mod.write(report_mod.read_rows(os.path.join(args.report, "flights.csv")), args.report)
        print(text)
        print("report: %s" % os.path.join(args.report, "report", "report.html"))
        return 0

    iface = plan_mod.discover()
    classes = iface.classes
    if args.classes:
        classes = tuple(c.strip() for c in args.classes.split(",") if c.strip())
        unknown = [c for c in classes if c not in iface.classes]
        if unknown:
            ap.error("unknown fault class %s (available: %s)" % (", ".join(unknown), ", ".join(iface.classes)))
    lo, hi = (float(v) for v in args.fault_window.split(","))
    plan = plan_mod.make_plan(args.flights, args.seed, classes, duration_s=args.duration,
                              fault_window_s=(lo, hi), interface=iface, ha=args.ha,
                              aircraft=args.aircraft)
    out = args.out or os.path.join(ROOT, "hil", "out", "campaign-%s-%d" % (
        datetime.datetime.utcnow().strftime("%Y-%m-%d_%H%M%S"), args.seed))
    if args.plan_only:
        for fl in plan:
            folder = os.path.join(out, "flights", "%04d-%s-%d" % (fl.flight_id, fl.fault_class, fl.seed))
            print("#%d %s: %s" % (fl.flight_id, fl.fault_class, plan_mod.shell(plan_mod.command(fl, folder, iface))))
        return 0

    from hil.campaigns import runner
    print("campaign: %d flights of %g s over %s, seed %d, HA %s, on %s; table: %s" % (
        len(plan), args.duration, ",".join(classes), args.seed, args.ha,
        args.scheduler or "a LocalCluster of %d workers" % (args.workers or os.cpu_count() or 1),
        os.path.join(out, "flights.csv")), file=sys.stderr)
    rows = runner.run_campaign(plan, iface, out, scheduler=args.scheduler, workers=args.workers,
                               wall_limit_s=args.wall_limit, progress=not args.no_progress)
    _, text = report_mod.write(report_mod.read_rows(os.path.join(out, "flights.csv")), out)
    print(text)
    print("report: %s" % os.path.join(out, "report", "report.html"))
    broke = sum(1 for r in rows if r["broke_property"])
    lost = sum(1 for r in rows if r["status"] in ("died", "timeout"))
    return 1 if broke or lost else 0


if __name__ == "__main__":
    sys.exit(main())
