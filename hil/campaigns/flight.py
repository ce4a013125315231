"""One flight of a campaign under its own wall-clock limit, and its row of the campaign table.

The flight (hil/run_flight.py) runs in its own process group and session; the processes it starts
(its master when it has its own, roslaunch and every node, a controller hp_supervisor restarts)
each get their own group, so the flight is told apart by a token in the environment every one of
them inherits. Past the wall-clock limit the flight gets SIGTERM (run_flight.py stops what it
started), then every process group holding the token gets SIGKILL, until none is left: Dask cannot
cancel a running task, so this wrapper is what enforces the limit. A flight that dies or runs out of time gives a row all
the same, with its status and reason."""
import json
import math
import os
import signal
import socket
import subprocess
import sys
import time
import uuid

from hil import proc_stat

TOKEN_VAR = "HIL_CAMPAIGN_FLIGHT"
# The row's columns, in order (the CSV's header).
COLUMNS = ["flight_id", "fault_class", "seed", "fault_at_s", "fault_duration_s", "fault_params",
           "wind_mps", "wind_from_deg", "turbulence", "beyond_design_wind", "ha", "status", "reason", "took_effect", "ok", "broke_property", "unsafe_commands",
           "envelope_violations_under_ha_s", "sx_inherited_from_hp_s", "sx_left_under_ha_s",
           "max_sx_row_under_ha", "takeover_latency_s", "takeover_within_one_period", "aircraft_crashed",
           "recovery_s", "latched", "stalled_under_ha_s", "longest_stall_under_ha_s", "stalled_from_fault_s",
           "recovery_height_loss_ft",
           "min_height_agl_ft", "min_airspeed_margin_ftps",
           "mission_progress", "simulated_s", "flight_duration_s", "wall_s", "x_real_time",
           "exit_code", "leftovers_killed", "worker", "master", "folder", "command"]


def holders(token, skip=None, var=TOKEN_VAR):
    """pid -> process group of every process whose environment holds this flight's token (var:
    the variable that holds it).
    skip: a set of pids known not to hold it, not read again, and to which every pid read
    without it is added (a caller that polls reads each process's environment once)."""
    needle = ("%s=%s" % (var, token)).encode()
    found = {}
    me = os.getpid()
    for pid in os.listdir("/proc"):
        if not pid.isdigit() or int(pid) == me or (skip is not None and int(pid) in skip):
            continue
        try:
            with open("/proc/%s/environ" % pid, "rb") as f:
                env = f.read().split(b"\0")
            if needle in env:
                found[int(pid)] = os.getpgid(int(pid))
            elif skip is not None and env != [b""]:  # empty while a process execs: read again
                skip.add(int(pid))
        except (OSError, ProcessLookupError):
            continue
    return found


def kill_all(token, popen=None, bound_s=30.0, var=TOKEN_VAR):
    """SIGKILL every process group of the flight until no process holds its token; returns how
    many processes were found. The flight's own group first (its leader may be a zombie until
    reaped, which is why it is reaped here)."""
    killed = set()
    deadline = time.monotonic() + bound_s
    while True:
        if popen is not None and popen.poll() is None:  # reaped: its pid may be another's
            try:
                os.killpg(popen.pid, signal.SIGKILL)
            except (ProcessLookupError, PermissionError):
                pass
        found = holders(token, var=var)
        for pid, pgid in found.items():
            killed.add(pid)
            for target in (lambda: os.killpg(pgid, signal.SIGKILL), lambda: os.kill(pid, signal.SIGKILL)):
                try:
                    target()
                except (ProcessLookupError, PermissionError):
                    pass
        if popen is not None and popen.returncode is None:
            try:
                popen.wait(timeout=0.2)
            except subprocess.TimeoutExpired:
                pass
        # Zombies still show their environment until their parent reaps them; a zombie is dead.
        if not [p for p in holders(token, var=var) if not proc_stat.dead(p)]:
            return len(killed)
        if time.monotonic() > deadline:
            return len(killed)
        time.sleep(0.1)


def _num(v):
    return None if v is None or (isinstance(v, float) and math.isnan(v)) else v


def broke_property(row):
    """The Simplex property: no servo command outside S_u, the aircraft inside S_x while the HA
    flies, and the flight's own verdict (hil.verdicts'). Beyond the aircraft's design wind
    (hil/design_wind.py) it is claimed no more: such a flight is judged on survival, no unsafe
    command and no crash."""
    if row["status"] not in ("ok", "fault_not_effective"):
        return False  # not known: such flights are listed as died / timed out
    if row.get("beyond_design_wind"):
        return bool((row["unsafe_commands"] or 0) > 0 or row.get("aircraft_crashed"))
    env = row["envelope_violations_under_ha_s"]
    return bool((row["unsafe_commands"] or 0) > 0 or env is None or (isinstance(env, float) and math.isnan(env))
                or env > 0 or row["ok"] is False)


def _run_killed_whole(argv, timeout_s, env, term_grace_s, stdout):
    """The one way a flight is run: to its end or past timeout_s, then SIGTERM to its session,
    term_grace_s to go, and every process holding its token SIGKILLed. subprocess.run's own
    timeout would SIGKILL run_flight.py alone and orphan its master and nodes. Returns (exit code,
    output bytes or None when stdout is a file, timed out, processes found after the end)."""
    token = uuid.uuid4().hex
    env = dict(env if env is not None else os.environ)
    env[TOKEN_VAR] = token
    p = subprocess.Popen(argv, env=env, stdout=stdout, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                         start_new_session=True)
    timed_out = False
    try:
        out, _ = p.communicate(timeout=timeout_s)
    except subprocess.TimeoutExpired:
        timed_out = True
        try:
            os.killpg(p.pid, signal.SIGTERM)
            out, _ = p.communicate(timeout=term_grace_s)
        except (ProcessLookupError, subprocess.TimeoutExpired):
            kill_all(token, p)
            out, _ = p.communicate()
    return p.returncode, out, timed_out, kill_all(token)


def run_whole(argv, timeout_s, env=None, term_grace_s=30.0):
    """Runs argv (a run_flight.py command) for a test and leaves no process of it behind:
    (exit code, output bytes, timed out)."""
    code, out, timed_out, _ = _run_killed_whole(argv, timeout_s, env, term_grace_s, subprocess.PIPE)
    return code, out, timed_out


def run_completed(argv, timeout, env=None, term_grace_s=30.0):
    """subprocess.run(argv, stdout=PIPE, stderr=STDOUT, timeout=timeout) for a flight, killed
    whole (run_whole) when it runs out of time, which it reports as subprocess.TimeoutExpired."""
    code, out, timed_out = run_whole(argv, timeout, env=env, term_grace_s=term_grace_s)
    if timed_out:
        raise subprocess.TimeoutExpired(argv, timeout, output=out)
    return subprocess.CompletedProcess(argv, code, stdout=out)


SHARED_FLIGHTS_VAR = "HIL_TEST_FLIGHTS"


def run_once_per_test_run(argv, timeout):
    """run_completed(argv + ["--folder", folder]) for a test, flown once per test run: the tests
    that read one scenario (the same run_flight.py command line) share its flight, across modules
    and pytest-xdist workers. The test run's folder for them is $HIL_TEST_FLIGHTS (conftest.py
    makes one per run); without it every call flies. Returns (CompletedProcess, folder); lockstep
    is deterministic, so a reader gets the flight it would have flown itself."""
    import fcntl
    import hashlib
    base = os.environ.get(SHARED_FLIGHTS_VAR)
    if not base:
        import tempfile
        folder = os.path.join(tempfile.mkdtemp(prefix="hil_flight_"), "flight")
        return run_completed(list(argv) + ["--folder", folder], timeout), folder
    key = hashlib.sha256(json.dumps(list(argv[1:])).encode()).hexdigest()[:16]
    folder = os.path.join(base, key, "flight")
    with open(os.path.join(base, key + ".lock"), "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)  # a second reader waits here for the first one's flight
        done = os.path.join(base, key + ".json")
        if not os.path.exists(done):
            r = run_completed(list(argv) + ["--folder", folder], timeout)
            with open(done, "w") as f:
                json.dump({"argv": r.args, "returncode": r.returncode,
                           "stdout": r.stdout.decode(errors="replace")}, f)
        with open(done) as f:
            d = json.load(f)
    return subprocess.CompletedProcess(d["argv"], d["returncode"], stdout=d["stdout"].encode()), folder


def run(flight, argv, folder, wall_limit_s, term_grace_s=30.0, env=None, master_uri=None):
    """Flies one flight (argv: its command) and returns its row. Never raises for what the flight
    does: a flight that fails gives a row with status died or timeout. master_uri: a ROS master
    kept by the worker to fly on (run_flight.py --master); the row's command flies on a master of
    its own, which lockstep makes the same flight."""
    os.makedirs(folder, exist_ok=True)
    row = {c: None for c in COLUMNS}
    row.update(flight_id=flight.flight_id, fault_class=flight.fault_class, seed=flight.seed,
               fault_at_s=flight.fault_at_s, fault_duration_s=flight.fault_duration_s,
               fault_params=json.dumps(dict(flight.params), sort_keys=True),
               wind_mps=getattr(flight, "wind_mps", 0.0), wind_from_deg=getattr(flight, "wind_from_deg", 0.0),
               turbulence=getattr(flight, "turbulence", "none"), ha=getattr(flight, "ha", "sil"),
               flight_duration_s=flight.duration_s, folder=folder,
               command=" ".join(_quote(a) for a in argv), worker=socket.gethostname(),
               master="kept" if master_uri else "own")
    flown = list(argv) + (["--master", master_uri] if master_uri else [])
    t0 = time.monotonic()
    with open(os.path.join(folder, "campaign_flight.log"), "wb") as log:
        code, _, timed_out, row["leftovers_killed"] = _run_killed_whole(flown, wall_limit_s, env, term_grace_s, log)
    row["wall_s"] = round(time.monotonic() - t0, 2)
    row["exit_code"] = code
    summary = None
    try:
        with open(os.path.join(folder, "summary.json")) as f:
            summary = json.load(f)
    except (OSError, ValueError):
        pass
    if timed_out:
        row["status"] = "timeout"
        row["reason"] = "past the wall-clock limit of %g s: killed whole" % wall_limit_s
    elif summary is None or code != 0 or summary.get("status") in ("died", "timeout"):
        # run_flight.py says why in a summary of its own when it can (its own --timeout-s too).
        s = summary or {}
        row["status"] = "timeout" if s.get("status") == "timeout" else "died"
        row["reason"] = ("exit %s: %s" % (code, s["error"])) if s.get("error") else _death_reason(folder, code)
    elif not isinstance(summary.get("verdict"), dict) or not isinstance(summary.get("fault"), dict):
        # The verdict is hil.verdicts' alone: a summary without one is not judged here again.
        row["status"] = "died"
        row["reason"] = "summary.json has no verdict or no fault record (not written by this run_flight.py)"
    else:
        row["status"] = summary.get("status") or "ok"
    if row["status"] in ("died", "timeout"):
        # No world in its summary: its planned wind says which of the report's tables it is in
        # (campaign seed 26: a cold_start parked in 10.8 m/s died and was counted inside).
        from hil.campaigns import plan as plan_mod
        row["beyond_design_wind"] = "; ".join(plan_mod.beyond_design_wind(flight))
    if row["status"] not in ("died", "timeout"):
        v, f = summary["verdict"], summary["fault"]
        row["took_effect"] = f.get("took_effect")
        for k in ("ok", "unsafe_commands", "envelope_violations_under_ha_s", "takeover_latency_s", "recovery_s",
                  "latched", "min_height_agl_ft", "min_airspeed_margin_ftps", "mission_progress",
                  "stalled_under_ha_s", "longest_stall_under_ha_s", "stalled_from_fault_s",
                  "recovery_height_loss_ft"):
            row[k] = _num(v.get(k)) if k != "envelope_violations_under_ha_s" else v.get(k)
        env = v.get("envelope_under_ha") or {}
        row["sx_inherited_from_hp_s"] = env.get("inherited_from_hp_s")
        row["sx_left_under_ha_s"] = env.get("left_under_ha_s")
        row["max_sx_row_under_ha"] = env.get("max_S_x_row")
        row["takeover_within_one_period"] = v.get("takeover_within_one_period")
        row["aircraft_crashed"] = v.get("aircraft_crashed")
        row["beyond_design_wind"] = "; ".join((summary.get("world") or {}).get("beyond_design_wind") or [])
        row["simulated_s"] = summary.get("simulated_s")
        row["x_real_time"] = summary.get("x_real_time")
        if row["status"] == "ok" and row["took_effect"] is False:
            row["status"] = "fault_not_effective"
        if row["status"] != "ok" and not row["reason"]:
            row["reason"] = (summary.get("fault") or {}).get("evidence") or row["status"]
    row["broke_property"] = broke_property(row)
    return row


def _death_reason(folder, code):
    for name in ("error.txt",):
        try:
            with open(os.path.join(folder, name)) as f:
                return "exit %s: %s" % (code, f.read().strip()[:300])
        except OSError:
            pass
    try:
        with open(os.path.join(folder, "campaign_flight.log"), errors="replace") as f:
            lines = [ln.strip() for ln in f.read().splitlines() if ln.strip()]
        tail = lines[-1][:300] if lines else "no output"
    except OSError:
        tail = "no output"
    if code is not None and code < 0:
        return "killed by signal %d: %s" % (-code, tail)
    return "exit %s: %s (logs: %s)" % (code, tail, folder)


def _quote(a):
    import shlex
    return shlex.quote(a)


if __name__ == "__main__":
    sys.exit("hil/campaigns/flight.py is a module: hil/campaign.py runs campaigns")
