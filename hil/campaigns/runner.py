"""Runs a campaign's flights on Dask, one flight per task, and streams each row to the campaign's
CSV as its flight finishes (in the order they finish), with a progress bar on stderr.

LocalCluster by default (one single-threaded worker process per core, on loopback); a scheduler
address (tcp://HOST:8786) runs the same plan on a cluster a lab already has: its workers need this
checkout at the same path with its workspace built and sourced (dask-worker started from a shell
where `source .build/ws/devel/setup.bash` was run). The flight wrapper is sent to the workers by
value, so they need no Python path set up for it. A task that Dask loses (its worker died) gives
a row with status died, never a missing row."""
import csv
import json
import math
import os
import sys
import time
import xmlrpc.client

from . import flight as flight_mod
from . import kept_master
from . import plan as plan_mod


def _fly(flight, argv, folder, wall_limit_s, kept=False):
    """One flight on a worker: on the worker's kept master when the campaign keeps them, else (or
    when that master cannot be had) on a master of the flight's own."""
    master_uri = None
    if kept:
        from distributed import get_worker
        plugin = get_worker().plugins.get(kept_master.PLUGIN_NAME)
        try:
            master_uri = plugin.ensure() if plugin is not None else None
        except (RuntimeError, OSError, xmlrpc.client.Error):  # not up, setpriv missing, refused
            master_uri = None
    return flight_mod.run(flight, argv, folder, wall_limit_s, master_uri=master_uri)


class CsvSink:
    """Appends rows as they come, flushed to disk at once (a reader sees every finished flight)."""

    def __init__(self, path):
        self.path = path
        self.f = open(path, "w", newline="")
        self.w = csv.DictWriter(self.f, fieldnames=flight_mod.COLUMNS, extrasaction="ignore")
        self.w.writeheader()
        self.f.flush()

    def write(self, row):
        self.w.writerow({k: _cell(row.get(k)) for k in flight_mod.COLUMNS})
        self.f.flush()
        os.fsync(self.f.fileno())

    def close(self):
        self.f.close()


def _cell(v):
    if v is None:
        return ""
    if isinstance(v, float) and math.isnan(v):
        return "nan"
    return v


class Progress:
    def __init__(self, total, stream=sys.stderr, enabled=True):
        self.total, self.stream, self.enabled = total, stream, enabled
        self.t0 = time.monotonic()
        self.counts = {}
        self.done = self.broke = 0

    def update(self, row):
        self.done += 1
        self.counts[row["status"]] = self.counts.get(row["status"], 0) + 1
        self.broke += bool(row.get("broke_property"))
        if not self.enabled:
            return
        width = 30
        fill = int(round(width * self.done / self.total))
        wall = time.monotonic() - self.t0
        eta = wall / self.done * (self.total - self.done)
        extra = " ".join("%s %d" % kv for kv in sorted(self.counts.items()))
        if self.broke:
            extra += "  BROKE THE PROPERTY %d" % self.broke
        self.stream.write("\r[%s%s] %d/%d flights  %s  %s elapsed, %s left " % (
            "#" * fill, "-" * (width - fill), self.done, self.total, extra, _hms(wall), _hms(eta)))
        if self.done == self.total:
            self.stream.write("\n")
        self.stream.flush()


def _hms(s):
    s = int(s)
    return "%d:%02d:%02d" % (s // 3600, s % 3600 // 60, s % 60)


def local_cluster(workers=None):
    from distributed import LocalCluster
    workers = workers or os.cpu_count() or 1
    # One flight at a time per worker process, everything on loopback: the scheduler's and the
    # workers' HTTP servers too (with no address given, the scheduler's listens on every interface).
    return LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, host="127.0.0.1",
                        dashboard_address="127.0.0.1:0", worker_dashboard_address="127.0.0.1:0",
                        silence_logs=40)


def run_campaign(plan, interface, out_dir, scheduler=None, workers=None, wall_limit_s=None,
                 progress=True, on_row=None, python=None, run_flight=plan_mod.RUN_FLIGHT):
    """Flies every flight of plan, writing out_dir/flights.csv as they finish; returns the rows
    (in plan order). wall_limit_s: each flight's limit (default from its simulated length);
    on_row(row) is called in this process as each row is written; run_flight: what flies one."""
    import uuid
    import cloudpickle
    from distributed import Client, as_completed
    cloudpickle.register_pickle_by_value(flight_mod)
    cloudpickle.register_pickle_by_value(kept_master)
    os.makedirs(out_dir, exist_ok=True)
    python = python or sys.executable
    with open(os.path.join(out_dir, "plan.json"), "w") as f:
        f.write(plan_mod.to_json(plan))
    cluster = None
    if scheduler is None:
        cluster = local_cluster(workers)
        client = Client(cluster)
    else:
        client = Client(scheduler)
    # Each worker keeps a ROS master for its flights (a master and rosout of a flight's own cost
    # 0.9-1.0 s of CPU a flight on the slow machine, a kept one about 0.3 s); their processes
    # hold this campaign's token.
    kept = bool(getattr(interface, "has_master", False))
    token = uuid.uuid4().hex
    if kept:
        client.register_worker_plugin(kept_master.KeptMaster(token), name=kept_master.PLUGIN_NAME)
    sink = CsvSink(os.path.join(out_dir, "flights.csv"))
    bar = Progress(len(plan), enabled=progress)
    rows = {}
    t0 = time.monotonic()
    try:
        futures = {}
        for fl in plan:
            folder = os.path.join(os.path.abspath(out_dir), "flights", "%04d-%s-%d" % (fl.flight_id, fl.fault_class, fl.seed))
            argv = plan_mod.command(fl, folder, interface, run_flight=run_flight, python=python)
            limit = wall_limit_s or default_wall_limit_s(fl.duration_s)
            fut = client.submit(_fly, fl, argv, folder, limit, kept, key="flight-%d-%s" % (fl.flight_id, os.urandom(4).hex()),
                                pure=False)
            futures[fut] = (fl, argv, folder)
        for fut in as_completed(list(futures)):
            fl, argv, folder = futures[fut]
            try:
                row = fut.result()
            except Exception as e:  # the task itself was lost: the flight is reported, not dropped
                row = {c: None for c in flight_mod.COLUMNS}
                row.update(flight_id=fl.flight_id, fault_class=fl.fault_class, seed=fl.seed,
                           fault_at_s=fl.fault_at_s, fault_duration_s=fl.fault_duration_s,
                           fault_params=json.dumps(dict(fl.params), sort_keys=True), ha=fl.ha, status="died",
                           reason="the task failed on Dask: %s: %s" % (type(e).__name__, str(e)[:200]),
                           flight_duration_s=fl.duration_s, folder=folder, command=plan_mod.shell(argv),
                           broke_property=False)
            rows[fl.flight_id] = row
            sink.write(row)
            bar.update(row)
            if on_row is not None:
                on_row(row)
    finally:
        sink.close()
        if kept:
            try:
                client.unregister_worker_plugin(kept_master.PLUGIN_NAME)  # stops the masters
            except Exception as e:  # a worker gone: its master died with it, or the sweep finds it
                print("campaign: the workers' masters were not all stopped by Dask: %s" % e, file=sys.stderr)
        client.close()
        if cluster is not None:
            cluster.close()
        if kept:
            flight_mod.kill_all(token, var=kept_master.CAMPAIGN_VAR)
    wall = time.monotonic() - t0
    with open(os.path.join(out_dir, "campaign.json"), "w") as f:
        json.dump({"flights": len(plan), "wall_s": round(wall, 2),
                   "classes": sorted({fl.fault_class for fl in plan}),
                   "flight_duration_s": sorted({fl.duration_s for fl in plan}),
                   "scheduler": scheduler or "LocalCluster(%d workers)" % (workers or os.cpu_count() or 1),
                   # The workers' masters hold it as HIL_CAMPAIGN: what finds one left behind.
                   "ros_masters": "kept per worker" if kept else "one per flight", "token": token},
                  f, indent=1)
    return [rows[fl.flight_id] for fl in plan]


def default_wall_limit_s(duration_s):
    """Generous: a 45 s flight takes some 20-60 s on two shared cores; a stuck one is what this
    catches (a participant may take 10 s a step before it counts as gone)."""
    return 300.0 + 10.0 * duration_s
