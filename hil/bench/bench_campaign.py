#!/usr/bin/env python3
"""The campaign part of make bench-hil: a seeded campaign of FLIGHTS lockstep flights (default
150, BENCH_HIL_FLIGHTS overrides) of SECONDS simulated each over every fault class, on a
LocalCluster of one worker per core, and the Simplex property over all of them:

  flights                        flights in the campaign (and how many died or timed out)
  unsafe_commands                servo commands outside S_u, summed over the flights (target 0)
  envelope_violations_under_ha   seconds outside S_x while the HA flew, summed (target 0)
  stalled_under_ha               seconds with the wing past its stall alpha while the HA flew (target 0)
  recovery_height_loss           height lost from a takeover to the recovery, p50 and max
  wind                           the strongest wind flown (each flight draws its own)
  takeover_latency_p99           deadline miss to the HA's command on the servos, p99 over every
                                 takeover (target: within one HA period)
  recovery_crash_p50/p99         crash faults: the fault to the HP back in control (target < 10 s)
  flights_per_hour               campaign throughput on this machine
  campaign_speed                 simulated seconds of all flights / the campaign's wall time

The campaign's folder (flights.csv, report/report.html) is printed on stderr with its table.
Wall time on a shared machine measures the neighbours too."""
import math
import os
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
from hil.campaigns import plan as plan_mod  # noqa: E402
from hil.campaigns import report as report_mod  # noqa: E402
from hil.campaigns import runner  # noqa: E402

FLIGHTS = int(os.environ.get("BENCH_HIL_FLIGHTS", "150"))
SECONDS = float(os.environ.get("BENCH_HIL_FLIGHT_S", "40"))
SEED = int(os.environ.get("BENCH_HIL_SEED", "1"))


def figures(rows, wall_s):
    flown = [r for r in rows if r["status"] in ("ok", "fault_not_effective")]
    lat = [r["takeover_latency_s"] for r in flown if r["takeover_latency_s"] is not None]
    rec = [r["recovery_s"] for r in flown if r["fault_class"] == "crash" and r["recovery_s"] is not None]
    crashes = sum(1 for r in flown if r["fault_class"] == "crash")
    env = [r["envelope_violations_under_ha_s"] for r in flown if r["envelope_violations_under_ha_s"] is not None]
    unknown_env = sum(1 for v in env if math.isnan(v))
    simulated = sum(r["simulated_s"] or 0.0 for r in flown)
    lost = len(rows) - len(flown)
    out = [("flights", "%d flights (%d died or timed out, %d fault not effective, %d classes)" % (
        len(rows), lost, sum(1 for r in rows if r["status"] == "fault_not_effective"),
        len({r["fault_class"] for r in rows})))]
    out.append(("unsafe_commands", "%d commands (target 0)" % sum(int(r["unsafe_commands"] or 0) for r in flown)))
    out.append(("envelope_violations_under_ha", "%.2f s (target 0%s)" % (
        sum(v for v in env if not math.isnan(v)),
        "; %d flights left S_x for an unknown time" % unknown_env if unknown_env else "")))
    stalled = [r for r in flown if (r.get("stalled_under_ha_s") or 0.0) > 0.0]
    out.append(("stalled_under_ha", "%.2f s in %d flights (target 0: the wing past its stall alpha while the HA flew)" % (
        sum(r["stalled_under_ha_s"] for r in stalled), len(stalled))))
    loss = [r["recovery_height_loss_ft"] for r in flown if r.get("recovery_height_loss_ft") is not None]
    out.append(("recovery_height_loss", "p50 %s ft, max %s ft (%d flights with a takeover after the fault)" % (
        _f(report_mod.pct(loss, 50)), _f(max(loss) if loss else None), len(loss))))
    winds = [r.get("wind_mps") or 0.0 for r in rows]
    out.append(("wind", "up to %.1f m/s, %d of %d flights in wind" % (max(winds) if winds else 0.0,
                                                                     sum(1 for w in winds if w > 0.0), len(rows))))
    p99 = report_mod.pct(lat, 99)
    out.append(("takeover_latency_p99", "%s ms (%d takeovers, max %s ms; target: one HA period, 10 ms)" % (
        _f(p99, 1000.0), len(lat), _f(max(lat) if lat else None, 1000.0))))
    out.append(("recovery_crash_p50", "%s s (%d of %d crash flights recovered; target < 10 s)" % (
        _f(report_mod.pct(rec, 50)), len(rec), crashes)))
    out.append(("recovery_crash_p99", "%s s" % _f(report_mod.pct(rec, 99))))
    out.append(("flights_per_hour", "%.0f flights/h (%d flights in %.0f s wall, %d workers)" % (
        len(rows) / wall_s * 3600.0, len(rows), wall_s, os.cpu_count() or 1)))
    out.append(("campaign_speed", "%.2f x_realtime (%.0f s simulated in %.0f s wall)" % (simulated / wall_s, simulated, wall_s)))
    return out


def _f(v, scale=1.0):
    return "-" if v is None else "%.1f" % (v * scale) if scale != 1.0 else "%.2f" % v


def run(aircraft="DG808"):
    iface = plan_mod.discover()
    plan = plan_mod.make_plan(FLIGHTS, SEED, iface.classes, duration_s=SECONDS, fault_window_s=(8.0, 16.0),
                              interface=iface, aircraft=aircraft)
    out = tempfile.mkdtemp(prefix="bench_hil_campaign_")
    sys.stderr.write("bench-hil: campaign of %d flights of %g s over %d classes in %s\n" % (
        FLIGHTS, SECONDS, len(iface.classes), out))
    t0 = time.monotonic()
    runner.run_campaign(plan, iface, out, progress=sys.stderr.isatty())
    wall = time.monotonic() - t0
    rows = report_mod.read_rows(os.path.join(out, "flights.csv"))
    _, text = report_mod.write(rows, out)
    sys.stderr.write(text + "\nbench-hil: report %s\n" % os.path.join(out, "report", "report.html"))
    return figures(rows, wall)


def main():
    from bench_fdm import machine
    header = machine()
    for name, value in run():
        print("hil_campaign_%s: %s" % (name, value))
    print("machine: %s" % header)


if __name__ == "__main__":
    main()
