"""The campaign runner (hil/campaign.py, hil/campaigns/): the plan comes back the same from its
seed; a flight past its wall-clock limit is killed whole and reported as timed out; a flight that
dies is reported as died; rows reach the table as flights finish; a small real campaign on a
LocalCluster of two workers gives the table and the report. The quick cases fly
campaign_fake_flight.py (run_flight.py's command line, one way of ending per fault class)."""
import csv
import dataclasses
import json
import os
import subprocess
import sys
import time
import urllib.parse
import xmlrpc.client

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
from hil.campaigns import flight as flight_mod  # noqa: E402
from hil.campaigns import kept_master  # noqa: E402
from hil.campaigns import plan as plan_mod  # noqa: E402
from hil.campaigns import report as report_mod  # noqa: E402
from hil.campaigns import runner  # noqa: E402
from hil import proc_stat  # noqa: E402

FAKE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "campaign_fake_flight.py")
AGREED = plan_mod.Interface(classes=("quick", "wait", "die", "stuck", "unjudged"), fault_at_flag="--fault-at",
                            has_duration=True, has_params=True)


def wait_for(cond, what, bound_s=120.0):
    end = time.monotonic() + bound_s
    while not cond():
        if time.monotonic() > end:
            raise AssertionError("still not the case after %g s: %s" % (bound_s, what))
        time.sleep(0.05)


def my_children():
    """Live child processes of this test process, less multiprocessing's resource tracker (it
    serves every later multiprocessing user and ends when this process does)."""
    me = str(os.getpid())
    out = []
    for pid in os.listdir("/proc"):
        fields = proc_stat.stat_fields(pid) if pid.isdigit() else None
        if fields is None or fields[1] != me or fields[0] in proc_stat.DEAD:
            continue
        try:
            with open("/proc/%s/cmdline" % pid, "rb") as f:
                if b"resource_tracker" in f.read():
                    continue
        except OSError:
            continue
        out.append(int(pid))
    return out


def descendants(root):
    parent = {}
    for pid in os.listdir("/proc"):
        fields = proc_stat.stat_fields(pid) if pid.isdigit() else None
        if fields is not None:
            parent[int(pid)] = int(fields[1])
    out, pending = set(), [root]
    while pending:
        p = pending.pop()
        out.add(p)
        pending += [c for c, pp in parent.items() if pp == p and c not in out]
    return out


def listening_addresses(pids):
    """Local addresses of the TCP sockets these processes listen on (ss -ltnp)."""
    r = subprocess.run(["ss", "-ltnpH"], stdout=subprocess.PIPE, universal_newlines=True, check=True)
    out = []
    for line in r.stdout.splitlines():
        if any("pid=%d," % p in line for p in pids):
            out.append(line.split()[3])
    return out


def test_the_same_campaign_seed_gives_the_same_flights_and_commands():
    classes = ("crash", "hang", "nan_surface")
    a = plan_mod.make_plan(30, 7, classes, duration_s=40.0)
    b = plan_mod.make_plan(30, 7, classes, duration_s=40.0)
    assert a == b
    assert plan_mod.make_plan(30, 8, classes, duration_s=40.0) != a
    # Every class gets its share, and flight i is the same whatever the campaign's length.
    assert sorted({f.fault_class for f in a}) == sorted(classes)
    assert all(sum(f.fault_class == c for f in a) == 10 for c in classes)
    assert plan_mod.make_plan(12, 7, classes, duration_s=40.0) == a[:12]
    assert len({f.seed for f in a}) == len(a)
    f = a[4]
    argv = plan_mod.command(f, "/tmp/flight4", AGREED, python="python3")
    assert argv[:2] == ["python3", plan_mod.RUN_FLIGHT]
    assert argv[argv.index("--seed") + 1] == str(f.seed)
    assert argv[argv.index("--fault") + 1] == f.fault_class
    assert float(argv[argv.index("--fault-at") + 1]) == f.fault_at_s
    assert float(argv[argv.index("--fault-duration") + 1]) == f.fault_duration_s
    # The first lockstep flight's interface: the fault time goes to --crash-at, nothing else.
    first = plan_mod.Interface(classes=("crash", "hang"), fault_at_flag="--crash-at", has_duration=False,
                               has_params=False)
    argv = plan_mod.command(plan_mod.make_plan(2, 7, ("crash",), interface=first)[1], "/tmp/f", first)
    assert "--fault-duration" not in argv and float(argv[argv.index("--crash-at") + 1]) > 0


def test_every_flight_of_every_class_flies_its_own_wind_up_to_beyond_the_has_limit():
    """Issue 22's world: each flight draws a steady wind from any direction, up to 1.5 x
    sensors.max_wind_ftps but below 0.9 x the stall speed (no glider is launched in a wind it
    would fly in parked), and turbulence, whatever its fault class; run_flight.py gets it. A
    run_flight.py without the wind flags flies every flight calm, and the plan says so."""
    windy = plan_mod.Interface(classes=("crash", "stall"), fault_at_flag="--fault-at", has_duration=True,
                               has_params=True, has_wind=True)
    plan = plan_mod.make_plan(80, 3, windy.classes, interface=windy)
    limit_mps = plan_mod.max_wind_ftps("DG808") * 0.3048
    speeds = [f.wind_mps for f in plan]
    assert all(0.0 <= v <= min(1.5 * limit_mps, plan_mod.wind_draw_limit_ftps("DG808") * 0.3048) for v in speeds)
    assert plan_mod.wind_draw_limit_ftps("DG808") < 42.0  # limits.yaml's stall speed, DG808's
    assert max(speeds) > limit_mps and sum(v == 0.0 for v in speeds) >= 1   # beyond the limit; some calm
    assert {c for c in windy.classes} == {f.fault_class for f in plan if f.wind_mps > 0.0}
    assert max(f.wind_from_deg for f in plan) - min(f.wind_from_deg for f in plan) > 270.0
    assert {"none", "light", "moderate"} == {f.turbulence for f in plan}
    # The wind's own stream: the rest of each flight is the plan without wind.
    calm = plan_mod.make_plan(80, 3, windy.classes, interface=windy, wind=False)
    assert [dataclasses.replace(f, wind_mps=0.0, wind_from_deg=0.0, turbulence="none") for f in plan] == calm
    f = next(f for f in plan if f.wind_mps > 0.0)
    argv = plan_mod.command(f, "/tmp/f", windy)
    assert float(argv[argv.index("--wind-mps") + 1]) == f.wind_mps
    assert float(argv[argv.index("--wind-from-deg") + 1]) == f.wind_from_deg
    assert argv[argv.index("--turbulence") + 1] == f.turbulence
    assert all(f.wind_mps == 0.0 for f in plan_mod.make_plan(20, 3, AGREED.classes, interface=AGREED))
    assert "--wind-mps" not in plan_mod.command(plan[0], "/tmp/f", AGREED)


def test_a_campaign_with_ha_qemu_flies_every_flight_with_the_ha_in_qemu_and_the_same_plan_otherwise(tmp_path):
    """campaign.py --ha qemu: each flight's command (the one flown and the replay) takes --ha qemu,
    and the flights are those of the SIL campaign with the same seed."""
    argv = [sys.executable, os.path.join(ROOT, "hil", "campaign.py"), "--flights", "6", "--seed", "5",
            "--classes", "crash,hang", "--plan-only", "--out", "/tmp/c"]
    sil = subprocess.run(argv, stdout=subprocess.PIPE, check=True).stdout.decode().splitlines()
    qemu = subprocess.run(argv + ["--ha", "qemu"], stdout=subprocess.PIPE, check=True).stdout.decode().splitlines()
    assert len(qemu) == 6 and all(" --ha qemu " in line for line in qemu)
    assert not any("--ha" in line for line in sil)
    assert [line.replace(" --ha qemu", "") for line in qemu] == sil
    fl = plan_mod.make_plan(1, 5, ("quick",), ha="qemu", interface=AGREED)[0]
    folder = str(tmp_path)
    row = flight_mod.run(fl, plan_mod.command(fl, folder, AGREED, run_flight=FAKE), folder, 60.0)
    assert row["status"] == "ok" and row["ha"] == "qemu" and " --ha qemu " in row["command"]


def test_a_campaign_of_another_aircraft_flies_it_and_draws_its_winds_from_its_own_limits():
    """campaign.py --aircraft (make campaign AIRCRAFT=<name>): every flight flies that aircraft,
    and the winds are drawn up to its own limit (the Aerosonde's 55 ft/s stall launches in more
    wind than the DG808's 42)."""
    argv = [sys.executable, os.path.join(ROOT, "hil", "campaign.py"), "--flights", "40", "--seed", "5",
            "--classes", "crash,hang", "--plan-only", "--out", "/tmp/c"]
    lines = subprocess.run(argv + ["--aircraft", "Aerosonde"], stdout=subprocess.PIPE,
                           check=True).stdout.decode().splitlines()
    assert len(lines) == 40 and all(" --aircraft Aerosonde " in line for line in lines)
    own, dg808 = plan_mod.wind_draw_limit_ftps("Aerosonde"), plan_mod.wind_draw_limit_ftps("DG808")
    assert own > dg808
    windy = plan_mod.Interface(classes=("crash",), fault_at_flag="--fault-at", has_duration=True,
                               has_params=True, has_wind=True)
    speeds = [f.wind_mps / 0.3048 for f in plan_mod.make_plan(200, 5, ("crash",), interface=windy,
                                                             aircraft="Aerosonde")]
    assert max(speeds) <= own and max(speeds) > dg808


def test_a_flight_judged_ok_reaches_its_row_with_its_own_verdict(tmp_path):
    fl = plan_mod.make_plan(1, 5, ("quick",), interface=AGREED)[0]
    folder = str(tmp_path)
    row = flight_mod.run(fl, plan_mod.command(fl, folder, AGREED, run_flight=FAKE), folder, 60.0)
    assert row["status"] == "ok" and row["broke_property"] is False, row
    assert (row["recovery_s"], row["max_sx_row_under_ha"], row["min_height_agl_ft"]) == (4.5, 0.4, 150.0)


def test_a_summary_without_a_verdict_is_not_judged_again_but_reported_as_died(tmp_path):
    """The verdict is hil.verdicts' alone: the campaign does not recompute one from a summary's
    other fields (an older run_flight.py's schema)."""
    fl = plan_mod.make_plan(1, 5, ("unjudged",), interface=AGREED)[0]
    folder = str(tmp_path)
    row = flight_mod.run(fl, plan_mod.command(fl, folder, AGREED, run_flight=FAKE), folder, 60.0)
    assert row["status"] == "died" and "no verdict" in row["reason"], row
    assert row["unsafe_commands"] is None and row["broke_property"] is False


def test_the_classes_come_from_this_checkouts_run_flight():
    iface = plan_mod.discover()
    assert {"crash", "hang"} <= set(iface.classes)
    assert iface.fault_at_flag in ("--fault-at", "--crash-at")


def test_a_flight_past_its_wall_limit_is_killed_whole_and_reported_as_timed_out(tmp_path):
    folder = str(tmp_path)
    fl = plan_mod.Flight(0, "stuck", 5, 10.0, 1.0, (), 40.0)
    argv = plan_mod.command(fl, folder, AGREED, run_flight=FAKE)
    row = flight_mod.run(fl, argv, folder, wall_limit_s=15.0, term_grace_s=1.0)
    assert row["status"] == "timeout", row
    assert "killed whole" in row["reason"]
    with open(os.path.join(folder, "pids")) as f:
        pids = [int(p) for p in f.read().split()]
    assert len(pids) == 2, "the stuck flight had not started its processes within the limit"
    # Its processes in sessions of their own, one ignoring SIGTERM, are gone with it.
    for pid in pids:
        wait_for(lambda: proc_stat.dead(pid), "process %d of the timed-out flight gone" % pid, bound_s=30.0)
    assert row["exit_code"] == -9
    assert row["leftovers_killed"] == 0  # nothing of it was left for the sweep after the kill
    assert row["broke_property"] is False


def test_a_test_flight_past_its_timeout_raises_and_leaves_no_process_behind(tmp_path):
    """What the HiL tests run their flights with (run_completed): subprocess.run's own timeout
    would SIGKILL run_flight.py alone and leave its master and nodes flying."""
    folder = str(tmp_path)
    fl = plan_mod.Flight(0, "stuck", 5, 10.0, 1.0, (), 40.0)
    argv = plan_mod.command(fl, folder, AGREED, run_flight=FAKE)
    # Its run_flight.py ignores SIGTERM: a grace of 1 s, not a real flight's 30 s, before the
    # SIGKILL of everything holding its token (the same path, 29 s sooner).
    with pytest.raises(subprocess.TimeoutExpired):
        flight_mod.run_completed(argv, timeout=10.0, term_grace_s=1.0)
    with open(os.path.join(folder, "pids")) as f:
        pids = [int(p) for p in f.read().split()]
    assert len(pids) == 2, "the stuck flight had not started its processes within the timeout"
    for pid in pids:
        wait_for(lambda: proc_stat.dead(pid), "process %d of the timed-out flight gone" % pid, bound_s=30.0)


def test_a_test_flight_that_ends_gives_its_exit_code_and_output(tmp_path):
    folder = str(tmp_path)
    fl = plan_mod.Flight(0, "die", 5, 10.0, 1.0, (), 40.0)
    r = flight_mod.run_completed(plan_mod.command(fl, folder, AGREED, run_flight=FAKE), timeout=60.0)
    assert r.returncode == 3
    assert isinstance(r.stdout, bytes)


def test_a_flight_that_dies_is_reported_as_died_with_its_reason(tmp_path):
    folder = str(tmp_path)
    fl = plan_mod.Flight(3, "die", 9, 10.0, 1.0, (("bits", "2"),), 40.0)
    row = flight_mod.run(fl, plan_mod.command(fl, folder, AGREED, run_flight=FAKE), folder, wall_limit_s=300.0)
    assert row["status"] == "died"
    assert row["exit_code"] == 3
    assert "test death" in row["reason"]
    assert json.loads(row["fault_params"]) == {"bits": "2"}
    assert "--fault-param bits=2" in row["command"]
    assert row["beyond_design_wind"] == "", "a calm flight's death is inside the design wind"


def test_a_flight_that_dies_in_a_wind_past_the_design_wind_is_counted_beyond_it(tmp_path):
    # Campaign seed 26 #70: parked in 10.8 m/s the pitot is doubted, home never latches and the
    # mission is refused; with no summary world it was counted inside the design wind.
    folder = str(tmp_path)
    fl = plan_mod.Flight(4, "die", 9, 10.0, 1.0, (), 40.0, wind_mps=10.8, wind_from_deg=51.7)
    row = flight_mod.run(fl, plan_mod.command(fl, folder, AGREED, run_flight=FAKE), folder, wall_limit_s=300.0)
    assert row["status"] == "died"
    assert row["beyond_design_wind"].startswith("steady 35.4 ft/s"), row["beyond_design_wind"]


def test_a_real_flight_whose_launch_fails_is_reported_as_died_with_run_flights_reason(tmp_path):
    folder = os.path.join(str(tmp_path), "flight")
    iface = plan_mod.discover()
    fl = plan_mod.make_plan(1, 3, ("crash",), duration_s=20.0, interface=iface)[0]
    # An aircraft with no launch file: roscore comes up, roslaunch ends at once.
    argv = plan_mod.command(fl, folder, iface) + ["--aircraft", "NO_SUCH_AIRCRAFT"]
    row = flight_mod.run(fl, argv, folder, wall_limit_s=600.0)
    assert row["status"] == "died", row
    assert "launch ended before the flight did" in row["reason"]
    assert row["unsafe_commands"] is None and row["broke_property"] is False
    assert row["leftovers_killed"] == 0  # run_flight.py stopped its roscore itself


def test_rows_reach_the_table_as_flights_finish_and_none_is_dropped(monkeypatch, tmp_path):
    out = str(tmp_path)
    release = os.path.join(out, "release")
    monkeypatch.setenv("CAMPAIGN_TEST_RELEASE", release)
    plan = [plan_mod.Flight(0, "quick", 11, 10.0, 1.0, (), 40.0),
            plan_mod.Flight(1, "die", 12, 10.0, 1.0, (), 40.0),
            plan_mod.Flight(2, "wait", 13, 10.0, 1.0, (), 40.0)]
    seen, listening = [], []

    def on_row(row):
        seen.append(row["fault_class"])
        with open(os.path.join(out, "flights.csv")) as f:
            table = list(csv.DictReader(f))
        # What has finished is in the table while the "wait" flight is still flying.
        assert [r["fault_class"] for r in table] == seen
        if len(seen) == 2:
            assert "wait" not in seen
            # The scheduler, the workers and their HTTP servers listen on loopback only.
            addresses = listening_addresses(descendants(os.getpid()))
            listening.extend(addresses)
            open(release, "w").close()

    rows = runner.run_campaign(plan, AGREED, out, workers=2, progress=False, on_row=on_row, run_flight=FAKE)
    assert seen[-1] == "wait"
    assert len(listening) >= 3  # the scheduler and two workers at least
    assert all(a.startswith("127.0.0.1:") for a in listening), listening
    assert [r["status"] for r in rows] == ["ok", "died", "ok"]
    table = {r["flight_id"]: r for r in report_mod.read_rows(os.path.join(out, "flights.csv"))}
    assert sorted(table) == [0, 1, 2]
    assert table[0]["recovery_s"] == pytest.approx(4.5) and table[2]["takeover_latency_s"] == pytest.approx(0.01)
    assert table[1]["status"] == "died" and table[1]["recovery_s"] is None
    # The LocalCluster's workers are stopped with the campaign.
    wait_for(lambda: not my_children(), "the Dask workers stopped", bound_s=60.0)


def test_each_worker_keeps_one_ros_master_for_its_flights_and_none_outlives_the_campaign(tmp_path):
    out = str(tmp_path)
    kept = dataclasses.replace(AGREED, has_master=True)  # a run_flight.py that takes --master
    plan = [plan_mod.Flight(i, "quick", 30 + i, 10.0, 1.0, (), 40.0) for i in range(6)]
    rows = runner.run_campaign(plan, kept, out, workers=2, progress=False, run_flight=FAKE)
    assert [(r["status"], r["master"]) for r in rows] == [("ok", "kept")] * 6
    seen = []
    for r in rows:
        with open(os.path.join(r["folder"], "master.json")) as f:
            seen.append(json.load(f))
        assert "--master" not in r["command"]  # the replay flies on a master of its own
    assert all(m["code"] == 1 for m in seen)  # each flight's master answered it
    # Two workers, two masters, each serving several flights (a master a flight is 6 pids).
    assert 1 <= len({m["pid"] for m in seen}) <= 2 and len({m["uri"] for m in seen}) <= 2
    assert all(urllib.parse.urlparse(m["uri"]).hostname == "127.0.0.1" for m in seen)
    with open(os.path.join(out, "campaign.json")) as f:
        campaign = json.load(f)
    assert campaign["ros_masters"] == "kept per worker"
    wait_for(lambda: not my_children(), "the Dask workers stopped", bound_s=60.0)
    leftover = [p for p in flight_mod.holders(campaign["token"], var=kept_master.CAMPAIGN_VAR) if not proc_stat.dead(p)]
    assert leftover == [], "the workers' masters outlived the campaign"
    for m in seen:
        with pytest.raises(OSError):
            xmlrpc.client.ServerProxy(m["uri"]).getPid("/test")


def test_a_worker_that_cannot_start_its_master_flies_each_flight_on_a_master_of_its_own(monkeypatch, tmp_path):
    out = str(tmp_path / "campaign")
    # No rosmaster, rosout or setpriv to be found: the worker's master cannot be started.
    monkeypatch.setenv("PATH", str(tmp_path))
    kept = dataclasses.replace(AGREED, has_master=True)
    plan = [plan_mod.Flight(i, "quick", 40 + i, 10.0, 1.0, (), 40.0) for i in range(3)]
    rows = runner.run_campaign(plan, kept, out, workers=1, progress=False, run_flight=FAKE)
    assert [(r["status"], r["master"]) for r in rows] == [("ok", "own")] * 3
    assert not any(os.path.exists(os.path.join(r["folder"], "master.json")) for r in rows)
    wait_for(lambda: not my_children(), "the Dask workers stopped", bound_s=60.0)


def test_the_same_campaign_runs_on_a_scheduler_given_by_its_address(tmp_path):
    from distributed import LocalCluster
    out = str(tmp_path)
    plan = [plan_mod.Flight(i, "quick", 20 + i, 10.0, 1.0, (), 40.0) for i in range(3)]
    # A cluster that is already there, as a lab's would be: the campaign only knows its address.
    with LocalCluster(n_workers=1, threads_per_worker=1, processes=True, host="127.0.0.1",
                      dashboard_address="127.0.0.1:0", silence_logs=40) as cluster:
        rows = runner.run_campaign(plan, AGREED, out, scheduler=cluster.scheduler_address, progress=False,
                                   run_flight=FAKE)
        assert [r["status"] for r in rows] == ["ok"] * 3
        with open(os.path.join(out, "campaign.json")) as f:
            assert json.load(f)["scheduler"] == cluster.scheduler_address
        # The campaign left the cluster running: it was not its own.
        assert cluster.status.name == "running"
    wait_for(lambda: not my_children(), "the test's cluster stopped", bound_s=60.0)


def test_the_report_gives_nearest_rank_percentiles_and_lists_the_flights_that_broke_the_property(tmp_path):
    out = str(tmp_path)
    rows = []
    for i in range(101):
        rows.append({c: None for c in flight_mod.COLUMNS})
        rows[-1].update(flight_id=float(i), fault_class="crash" if i < 60 else "hang", seed=float(100 + i),
                        fault_at_s=10.0, status="ok", took_effect=True, ok=True, unsafe_commands=0.0,
                        envelope_violations_under_ha_s=0.0, takeover_latency_s=0.01 if i != 7 else 0.05,
                        recovery_s=float(i % 10), latched=False, min_height_agl_ft=100.0,
                        min_airspeed_margin_ftps=10.0, broke_property=False, command="replay %d" % i)
    rows[70].update(unsafe_commands=3.0, broke_property=True, ok=False)
    rows[80].update(status="timeout", takeover_latency_s=None, recovery_s=None, reason="past the limit")
    stats, text = report_mod.write(rows, out)
    by = {s["class"]: s for s in stats}
    assert by["all"]["flights"] == 101 and by["all"]["timeout"] == 1 and by["all"]["takeovers"] == 100
    assert by["all"]["takeover_p50_ms"] == pytest.approx(10.0)
    assert by["all"]["takeover_p99_ms"] == pytest.approx(10.0)  # one slow flight in 99 is the max, not p99
    assert by["all"]["takeover_max_ms"] == pytest.approx(50.0)
    assert by["crash"]["recovery_p50_s"] == 4.0 and by["crash"]["recovery_max_s"] == 9.0
    assert by["hang"]["unsafe_commands"] == 3 and by["hang"]["broke_property"] == 1
    assert "#70 hang seed 170" in text and "replay: replay 70" in text
    assert "#80 hang seed 180: timeout" in text
    for name in ("report.html", "table.md", "takeover_latency.png", "recovery_per_class.png",
                 "envelope_margins.png"):
        assert os.path.getsize(os.path.join(out, "report", name)) > 0
    with open(os.path.join(out, "report", "report.html")) as f:
        page = f.read()
    assert "replay 70" in page and "<img src='takeover_latency.png'>" in page


def test_a_small_real_campaign_on_two_workers_gives_the_table_and_the_report(tmp_path):
    out = str(tmp_path)
    iface = plan_mod.discover()
    plan = plan_mod.make_plan(3, 5, ("crash", "hang"), duration_s=20.0, fault_window_s=(8.0, 10.0),
                              interface=iface)
    assert iface.has_master  # run_flight.py takes --master: each worker keeps one for its flights
    rows = runner.run_campaign(plan, iface, out, workers=2, progress=False)
    assert [r["status"] for r in rows] == ["ok"] * 3, [(r["status"], r["reason"]) for r in rows]
    assert [r["master"] for r in rows] == ["kept"] * 3
    for r in rows:
        assert r["took_effect"] is True
        assert r["unsafe_commands"] == 0 and r["broke_property"] is False
        assert r["takeover_latency_s"] is not None and r["recovery_s"] is not None
    stats, text = report_mod.write(report_mod.read_rows(os.path.join(out, "flights.csv")), out)
    by = {s["class"]: s for s in stats}
    assert by["all"]["flights"] == 3 and by["all"]["takeovers"] == 3
    assert by["crash"]["flights"] + by["hang"]["flights"] == 3
    assert "flights that broke the property: 0" in text
    assert os.path.exists(os.path.join(out, "report", "report.html"))
    wait_for(lambda: not my_children(), "the Dask workers stopped", bound_s=60.0)
    # The last flight, flown on its worker's kept master (after another, with 3 on 2 workers), is the flight its replay
    # command flies alone on a master of its own: every truth message, byte for byte.
    alone = os.path.join(out, "alone")
    r = flight_mod.run_completed(plan_mod.command(plan[-1], alone, iface), timeout=600)
    assert r.returncode == 0, r.stdout.decode(errors="replace")[-3000:]
    with open(os.path.join(rows[-1]["folder"], "truth.bin"), "rb") as a, \
            open(os.path.join(alone, "truth.bin"), "rb") as b:
        assert a.read() == b.read()
