#!/usr/bin/env python3
"""Flies one HiL flight: the thesis's case study by default (32-waypoint mission uploaded through
microhard_gs, HP crash by SIGKILL at t = 100 s, HA takeover, restart, hand-back).

    hil/run_flight.py [--seed N] [--realtime] [--duration S] [--crash-at S] [--rate-hz HZ]
                      [--controller-hz HZ] [--out DIR] [--no-bag]
                      [--fault CLASS --fault-at S --fault-duration S --fault-param KEY=VALUE ...]
                      [--folder DIR] [--quiet] [--timeout-s S]
                      [--wind-mps M --wind-from-deg D --turbulence {none,light,moderate}]
                      [--ha {sil,qemu,due} [--due-port DEV --due-native-port DEV --due-ins-port DEV]]

--fault names a class of hil/faults (crash by default, at --crash-at: the case study); the
summary's "fault", "verdict" and "status" say whether it took effect and whether the Simplex
property held. Exit code 0 when the flight ran and its verdict was computed; otherwise the
summary still says why ("died": the simulator stopped, "timeout": past --timeout-s of wall time).

Each flight gets its own ROS master (a free port on loopback; or flies on the one --master names,
which a campaign's worker keeps for its flights), its own ptys and control socket
(a temporary folder) and its own output folder hil/out/<YYYY-MM-DD_HHMMSS>-<aircraft>-<seed>/
with flight.bag (hil/HIL_INTERFACES.md section 3), flight.tlog (the ground link's MAVLink),
summary.json and the logs. A progress bar goes to stderr. Every process started here is
stopped at the end, on Ctrl-C and on error. --realtime flies on the wall clock, with the ground
station's telemetry on UDP 14550 for QGroundControl. Needs the workspace sourced (make run does it)."""
import argparse
import datetime
import ipaddress
import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import sysconfig
import tempfile
import time
import urllib.parse
import uuid
import xmlrpc.client

HERE = os.path.dirname(os.path.abspath(__file__))
from hil import faults  # noqa: E402
from hil.aircraft_period import decision_rate_hz  # noqa: E402
from hil import proc_stat  # noqa: E402  (a process's /proc/PID/stat fields, one parser)
from hil import ros_master  # noqa: E402
from stack_tools.paths import ROOT  # noqa: E402  (aircraft/ of the source tree or the install)
from stack_tools.ports import free_port  # noqa: E402  (below the ephemeral range: nothing autobinds there)
# Python 3.12 dropped distutils: there setuptools' copy is the only one.
STDLIB_HAS_DISTUTILS = os.path.isdir(os.path.join(sysconfig.get_paths()["stdlib"], "distutils"))
# Every process of a run holds this run's token in its environment: what its leftover hunt looks for.
FLIGHT_VAR = "HIL_FLIGHT_RUN"
BAG_TOPICS = ["/hil/truth", "/decision_status", "/servo_op", "/pwm", "/ins", "/data", "/to_hil",
              "/way", "/home", "/rosout_agg", "/diagnostics"]


class Processes:
    """Everything this run started, each in its own process group, stopped in reverse order."""

    def __init__(self, env, log_dir):
        self.env, self.log_dir, self.procs = env, log_dir, []

    def start(self, name, argv):
        log = open(os.path.join(self.log_dir, name + ".log"), "w")
        p = subprocess.Popen(argv, env=self.env, stdout=log, stderr=subprocess.STDOUT,
                             start_new_session=True)
        self.procs.append((name, p, log))
        return p

    def stop_all(self):
        # Every one told at once, then each waited for: roslaunch, rosbag and the master each take
        # about a second to close (3.3 s a flight one after another, at load 4). Nothing needs
        # the master by now: a node's goodbye to it is refused at once, not waited out.
        for name, p, log in reversed(self.procs):
            if p.poll() is None:
                try:
                    os.killpg(p.pid, signal.SIGINT)  # roslaunch and rosbag close cleanly on SIGINT
                except ProcessLookupError:
                    pass
        deadline = time.monotonic() + 20.0
        for name, p, log in reversed(self.procs):
            try:
                p.wait(timeout=max(0.0, deadline - time.monotonic()))
            except subprocess.TimeoutExpired:
                os.killpg(p.pid, signal.SIGKILL)
                p.wait()
            # Its whole group, not the leader alone: `rosbag record` passes SIGINT on to its
            # recorder and exits at once, while the recorder is still closing the bag (a recorder
            # killed then as a leftover left flight.bag.active, and no flight.bag).
            while group_alive(p.pid) and time.monotonic() < deadline:
                time.sleep(0.01)
            log.close()
        self.procs = []


def group_alive(pgid):
    """A process of group pgid still runs (zombies aside: whoever reaps orphans here may not)."""
    for pid in os.listdir("/proc"):
        fields = proc_stat.stat_fields(pid) if pid.isdigit() else None
        if fields is not None and int(fields[2]) == pgid and fields[0] not in proc_stat.DEAD:
            return True
    return False


def start_master(procs, port, master_uri, stop):
    """The flight's own master, what roscore would make of it without roscore's own roslaunch:
    rosmaster with roscore's command line, /run_id (which every roslaunch checks and logs under),
    /rosversion and /rosdistro set as roscore sets them, and the rosout node (/rosout_agg, in the bag).
    roscore's roslaunch and its two `rosversion` processes were 1.2 s of CPU a flight, and
    closing it took a second. Returns once the master answers and this has set /run_id and
    started rosout (or at once when the run is being stopped); raises RuntimeError if the master
    does not answer within 60 s or rosout is not installed. The master is polled over its own
    XML-RPC here (a `rosparam get` per poll started a Python process each time, 0.3 s of CPU)."""
    procs.start("rosmaster", ["rosmaster", "--core", "-p", str(port), "-w", "3"])
    deadline = time.monotonic() + 60.0
    while not ros_master.answers(master_uri):
        if stop["now"]:
            return
        if time.monotonic() > deadline:
            raise RuntimeError("rosmaster did not come up on port %d" % port)
        time.sleep(0.05)
    ros_master.set_core_parameters(master_uri, ros_master.core_parameters())
    from roslib.packages import find_node
    rosout = find_node("rosout", "rosout")
    if not rosout:
        raise RuntimeError("the rosout node is not installed (package rosout)")
    procs.start("rosout", [rosout[0], "__name:=rosout"])


ROSCORE_XML = """<launch>
  <!-- The flight's roscore.xml (hil/run_flight.py, flight_etc_dir): the master is up before the
       flight's roslaunch starts, so only the parameters of this file reach the master, and
       start_master has set them without the two rosversion processes of the system's file. -->
  <group ns="/">
    <node pkg="rosout" type="rosout" name="rosout" respawn="true"/>
  </group>
</launch>
"""


def flight_etc_dir(run_dir, env):
    """ROS_ETC_DIR for the flight's processes: every roslaunch loads roscore.xml from there, and
    the system's runs `rosversion` twice for its two parameters (two Python processes, 0.2 s of
    CPU and 0.3 s of start-up a flight on the slow machine). Python nodes find their logging
    configuration in ROS_ETC_DIR too: ROS_PYTHON_LOG_CONFIG_FILE keeps them on the system's."""
    import rospkg
    etc = os.path.join(run_dir, "etc")
    os.makedirs(etc, exist_ok=True)
    with open(os.path.join(etc, "roscore.xml"), "w") as f:
        f.write(ROSCORE_XML)
    if not env.get("ROS_PYTHON_LOG_CONFIG_FILE"):
        system = rospkg.get_etc_ros_dir(env=env)
        for name in ("python_logging.conf", "python_logging.yaml"):
            if os.path.isfile(os.path.join(system, name)):
                env["ROS_PYTHON_LOG_CONFIG_FILE"] = os.path.join(system, name)
                break
    env["ROS_ETC_DIR"] = etc


def forget_flights_nodes(master_uri):
    """The flight's registrations and parameters removed from a kept master, once its processes
    are gone; a master that no longer answers has none to remove (the next flight on it is
    refused)."""
    try:
        ros_master.forget_nodes(master_uri)
        ros_master.clear_parameters(master_uri)
    except (OSError, xmlrpc.client.Error, RuntimeError) as e:
        print("run_flight: the flight's nodes were not unregistered from %s: %s" % (master_uri, e),
              file=sys.stderr)


def leftovers(token):
    """Processes of this run still alive (a controller hp_supervisor started after its own end,
    say), whatever group they ended up in: those whose environment holds the run's token
    (FLIGHT_VAR). Not the master's URI: a kept master and its rosout have that too."""
    found = []
    needle = ("%s=%s" % (FLIGHT_VAR, token)).encode()
    for pid in os.listdir("/proc"):
        if not pid.isdigit() or int(pid) == os.getpid():
            continue
        try:
            with open("/proc/%s/environ" % pid, "rb") as f:
                env = f.read().split(b"\0")
        except OSError:
            continue
        if needle in env:
            found.append(int(pid))
    return found


def progress_bar(t_s, total_s, wall_s):
    width = 40
    frac = max(0.0, min(1.0, t_s / total_s)) if total_s > 0 else 0.0
    fill = int(round(frac * width))
    speed = t_s / wall_s if wall_s > 0 else 0.0
    return "\r[%s%s] %6.1f / %.0f s simulated  %5.1fx real time " % ("#" * fill, "-" * (width - fill),
                                                                   t_s, total_s, speed)


REALTIME_NICE = -10


def raise_priority_for_realtime():
    """Real time: this process and every one it starts (the stack, the HA SIL, the simulator) at
    nice REALTIME_NICE when the system allows it (root or CAP_SYS_NICE). The Due and the HP
    computer are machines of their own; the development machine's other work is not the
    aircraft's, and at nice 0 a loaded machine starves the HP past two HA periods (a deadline
    miss the HA rightly takes over, restarts the HP for, and latches after; issue 24). Refused,
    the flight runs at the priority it has, and says so."""
    now = os.nice(0)
    if now <= REALTIME_NICE:
        return
    try:
        os.nice(REALTIME_NICE - now)
    except OSError as e:
        print("run_flight: real time at nice %d (%s): a loaded machine can make the HP miss deadlines" %
              (os.nice(0), e.strerror), file=sys.stderr)


def argument_parser():
    """run_flight.py's options."""
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--aircraft", default="DG808")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--realtime", action="store_true")
    ap.add_argument("--duration", type=float, default=240.0)
    ap.add_argument("--crash-at", type=float, default=100.0, help="when the HP fails (negative: never)")
    ap.add_argument("--fault", choices=faults.CLASSES + ("none",), default="crash",
                    help="a fault class of hil/faults (crash: SIGKILL of controller_<aircraft>; hang: SIGSTOP, ...)")
    ap.add_argument("--fault-at", type=float, default=None, help="when the fault starts (default: --crash-at)")
    ap.add_argument("--fault-duration", type=float, default=-1.0, help="how long it lasts (negative: to the end)")
    ap.add_argument("--fault-param", action="append", default=[], metavar="KEY=VALUE",
                    help="a parameter of the fault class (its module's docstring lists them)")
    ap.add_argument("--wind-mps", type=float, default=0.0, help="steady mean wind speed, m/s (calm by default)")
    ap.add_argument("--wind-from-deg", type=float, default=0.0,
                    help="where the mean wind blows from, deg true (meteorological: 0 = from the north)")
    ap.add_argument("--turbulence", choices=("none", "light", "moderate"), default="none",
                    help="Dryden turbulence on top of the mean wind (MIL-F-8785C low altitude)")
    ap.add_argument("--timeout-s", type=float, default=None, help="wall-clock limit: stop the flight past it (status timeout)")
    ap.add_argument("--rate-hz", type=float, default=None,
                    help="the HA's control rate (default: the aircraft's, its limits.yaml decision.rate_hz)")
    ap.add_argument("--controller-hz", type=float, default=None, help="default: the HA's rate")
    ap.add_argument("--out", default=os.path.join(HERE, "out"), help="parent of the flight folder")
    ap.add_argument("--folder", default=None, help="exact output folder (default: dated name)")
    ap.add_argument("--field-elevation-ft", type=float, default=None,
                    help="the field's elevation above sea level (default: the mission's home)")
    ap.add_argument("--temperature-c", type=float, default=None,
                    help="the day's temperature at the field (default: ISA there)")
    ap.add_argument("--ha", choices=("sil", "qemu", "due"), default="sil",
                    help="the HA in the loop: its host build (ha_sil), its Cortex-M3 machine code "
                         "on QEMU mps2-an385 (built into the flight's folder), or a "
                         "real Due flashed with make due-hil-image (--realtime only; the three "
                         "--due-*-port devices)")
    ap.add_argument("--due-port", default="/dev/ttyACM0",
                    help="with --ha due: the Due's programming port, the HP link")
    ap.add_argument("--due-native-port", default="/dev/ttyACM1",
                    help="with --ha due: the Due's native USB port, the simulator's records")
    ap.add_argument("--due-ins-port", default="/dev/ttyUSB0",
                    help="with --ha due: the USB-serial adapter wired to the Due's RX1 (VN-200 port 1)")
    ap.add_argument("--gcs-host", default="127.0.0.1", metavar="IPV4",
                    help="where the ground station's telemetry goes: a QGroundControl on another "
                         "machine (the vehicle then listens on every interface; default: this one)")
    ap.add_argument("--gcs-port", type=int, default=None,
                    help="its UDP port (default: 14550, QGroundControl's, in real time or with "
                         "--gcs-host; a free one for the simulator's own ground station otherwise)")
    ap.add_argument("--vehicle-port", type=int, default=None,
                    help="the vehicle's UDP port (default: 14555 in real time or with --gcs-host, "
                         "where a ground station expects it; a free one otherwise)")
    ap.add_argument("--master", default=None, metavar="URI",
                    help="fly on this ROS master, already running with its rosout (a campaign "
                         "worker keeps one for its flights): the last flight's parameters are "
                         "deleted first and this flight's registrations after (default: the "
                         "flight starts its own)")
    ap.add_argument("--no-bag", action="store_true")
    ap.add_argument("--quiet", action="store_true", help="no progress bar")
    return ap


def parse_args(argv):
    """The command line, checked (argparse's error and exit status 2 on a bad one): the
    arguments, and what follows from them for the launch."""
    ap = argument_parser()
    args = ap.parse_args(argv)
    fault_at = args.crash_at if args.fault_at is None else args.fault_at
    try:
        fault_params = faults.parse_params(args.fault_param)
        relay = args.fault != "none" and faults.needs_relay(args.fault)
        link_relay = args.fault != "none" and faults.needs_link_relay(args.fault)
    except ValueError as e:
        ap.error(str(e))
    if not (args.wind_mps >= 0.0 and args.wind_mps < 100.0):
        ap.error("--wind-mps must be in [0, 100)")
    if not (abs(args.wind_from_deg) <= 360.0):
        ap.error("--wind-from-deg must be in [-360, 360]")
    if any(" " in str(v) for v in fault_params.values()):
        ap.error("fault parameter values may not contain spaces")

    try:
        gcs_is_local = ipaddress.IPv4Address(args.gcs_host).is_loopback
    except ValueError:
        ap.error("--gcs-host must be an IPv4 address, got %r" % args.gcs_host)
    for name in ("gcs_port", "vehicle_port"):
        port_arg = getattr(args, name)
        if port_arg is not None and not 1 <= port_arg <= 65535:
            ap.error("--%s must be in 1..65535" % name.replace("_", "-"))
    # A ground station of the user's (QGroundControl) rather than the simulator's own monitor.
    external_gcs = args.realtime or args.gcs_host != "127.0.0.1" or args.gcs_port is not None
    if args.ha == "due" and not args.realtime:
        ap.error("--ha due needs --realtime: a Due keeps its own clock")
    if args.ha == "due" and link_relay:
        ap.error("--fault %s corrupts the HP link's bytes between the node and the HA: with --ha due "
                 "they go from the node straight to the Due's port" % args.fault)
    if args.ha == "due":
        missing = [p for p in (args.due_port, args.due_native_port, args.due_ins_port) if not os.path.exists(p)]
        if missing:
            ap.error("--ha due: no device at %s (is the Due plugged in, and the adapter on RX1?)" %
                     ", ".join(missing))
    if args.master is not None:
        uri = urllib.parse.urlparse(args.master)
        if uri.scheme != "http" or not uri.hostname or uri.port is None:
            ap.error("--master must be a ROS master's URI, http://HOST:PORT, got %r" % args.master)
    stamp = datetime.datetime.utcnow().strftime("%Y-%m-%d_%H%M%S")
    out = args.folder or os.path.join(args.out, "%s-%s-%d" % (stamp, args.aircraft, args.seed))
    # A folder that already holds a flight is never flown over: its done file would end the new
    # flight at once with the old one's result.
    if any(os.path.exists(os.path.join(out, f)) for f in ("done", "summary.json", "flight.bag")):
        ap.error("%s already holds a flight: give another --folder (flights are never overwritten)" % out)
    return args, argparse.Namespace(out=out, fault_at=fault_at, fault_params=fault_params, relay=relay,
                                    link_relay=link_relay, gcs_is_local=gcs_is_local,
                                    external_gcs=external_gcs)


def controller_rate_hz(args):
    """The controller's rate: --controller-hz, else the HA's (--rate-hz, else the aircraft's own,
    as the HA runs it). None for an aircraft with no limits.yaml: the launch then refuses the
    aircraft in check_config's words, which the run reports."""
    if args.controller_hz or args.rate_hz:
        return args.controller_hz or args.rate_hz
    try:
        return decision_rate_hz(os.path.join(ROOT, "aircraft", args.aircraft))
    except OSError:
        return None


def launch_command(args, d, run_dir, out, gs_bind, gs_remote):
    """The roslaunch of the flight's HiL launch file, with its arguments."""
    controller_hz = controller_rate_hz(args)
    rates = (["rate_hz:=%g" % args.rate_hz] if args.rate_hz else []) + \
        (["dt:=%g" % (1.0 / controller_hz)] if controller_hz else [])
    # --skip-log-check: the flight's log folder is its own and new; its size needs no `du`.
    launch = ["roslaunch", "--wait", "--skip-log-check", "drone_ros", "hil.launch", "aircraft:=" + args.aircraft,
              "run_dir:=" + run_dir, "out_dir:=" + out, "seed:=%d" % args.seed,
              "mode:=" + ("realtime" if args.realtime else "lockstep"),
              "duration_s:=%g" % args.duration, "crash_at_s:=%g" % args.crash_at, "fault:=" + args.fault,
              "fault_at_s:=%g" % d.fault_at, "fault_duration_s:=%g" % args.fault_duration,
              "fault_params:=" + " ".join("%s=%s" % kv for kv in sorted(d.fault_params.items())),
              "servo_relay:=%s" % ("true" if d.relay else "false"),
              "link_relay:=%s" % ("true" if d.link_relay else "false"),
              "wind_mps:=%g" % args.wind_mps, "wind_from_deg:=%g" % args.wind_from_deg,
              "turbulence:=" + args.turbulence,
              "gs_udp_bind_port:=%d" % gs_bind, "gs_udp_remote_port:=%d" % gs_remote,
              "gs_udp_remote_address:=" + args.gcs_host,
              "gs_udp_bind_address:=" + ("127.0.0.1" if d.gcs_is_local else "0.0.0.0"),
              "gs_monitor:=%s" % ("false" if d.external_gcs else "true"),
              "wait_for_recorder:=%s" % ("false" if args.no_bag else "true"),
              # The vehicle side of the ground link, beside the bag (microhard_gs/README.md).
              "gs_tlog_path:=" + ("" if args.no_bag else os.path.join(os.path.abspath(out), "flight.tlog"))] + rates
    if args.ha == "qemu":
        launch += ["ha:=qemu", "ha_image:=" + build_pil_image(os.path.join(out, "pil"), args.aircraft, args.realtime)]
    elif args.ha == "due":
        launch += ["ha:=due", "due_port:=" + args.due_port, "due_native_port:=" + args.due_native_port,
                   "due_ins_port:=" + args.due_ins_port]
    if args.field_elevation_ft is not None:
        launch.append("field_elevation_ft:=%r" % args.field_elevation_ft)
    if args.temperature_c is not None:
        launch.append("temperature_c:=%r" % args.temperature_c)
    return launch


def write_failed_summary(summary, out, args, d, status, error, code):
    """A flight that did not finish says so in its summary, never leaves it missing; returns
    the exit status."""
    if os.path.exists(os.path.join(out, "error.txt")):
        with open(os.path.join(out, "error.txt")) as f:
            error = "the simulator stopped: " + f.read().strip()
    failed = {"aircraft": args.aircraft, "seed": args.seed, "status": status, "error": error,
              "fault": {"class": args.fault, "at_s": d.fault_at, "duration_s": args.fault_duration,
                        "params": d.fault_params, "took_effect": False, "evidence": "the flight did not finish"},
              "verdict": None}
    with open(summary, "w") as f:
        json.dump(failed, f, indent=2)
    if error:
        print("run_flight: %s" % error, file=sys.stderr)
    return code or 1


class FlightTimeout(RuntimeError):
    """The flight ran past its wall-clock limit (--timeout-s)."""


def wait_for_done(args, launcher, out, stop):
    """Waits for the simulator's done file, drawing the progress bar; RuntimeError when the launch
    ends first, FlightTimeout past the wall-clock limit. Returns the done file's path."""
    t0 = time.monotonic()
    done = os.path.join(out, "done")
    while not stop["now"]:
        if os.path.exists(done):
            break
        if launcher.poll() is not None:
            raise RuntimeError("the launch ended before the flight did: see %s/launch.log" % out)
        if args.timeout_s is not None and time.monotonic() - t0 > args.timeout_s:
            raise FlightTimeout("past the wall-clock limit of %.0f s: stopped" % args.timeout_s)
        if not args.quiet:
            try:
                with open(os.path.join(out, "progress")) as f:
                    t_s, total = (float(v) for v in f.read().split())
                sys.stderr.write(progress_bar(t_s, total, time.monotonic() - t0))
                sys.stderr.flush()
            except (OSError, ValueError):
                pass
        time.sleep(0.05)
    if not args.quiet:
        sys.stderr.write("\n")
    return done


def flight_env(out, master_uri, run_dir):
    """The environment of every process of the flight: its master, loopback, its own ROS_HOME and
    logs, its token (FLIGHT_VAR) and its roscore.xml."""
    env = dict(os.environ, ROS_MASTER_URI=master_uri, ROS_HOSTNAME="127.0.0.1", ROS_IP="127.0.0.1",
               ROS_HOME=os.path.join(out, "ros"), ROS_LOG_DIR=os.path.join(out, "ros", "log"),
               PYTHONUNBUFFERED="1")
    env[FLIGHT_VAR] = uuid.uuid4().hex
    if STDLIB_HAS_DISTUTILS:
        # roslaunch imports rosclean, which imports distutils: setuptools' own copy unless this
        # says the standard library's (0.38 s of CPU a flight on a slow machine).
        env["SETUPTOOLS_USE_DISTUTILS"] = "stdlib"
    env.pop("ROS_NAMESPACE", None)
    flight_etc_dir(run_dir, env)
    return env


def main(argv=None):
    # Wall-clock marks of this run's phases (run_flight_times.json; hil/bench/bench_flight_overhead.py
    # puts them beside the simulator's sim_times.json): what every flight pays besides its steps.
    marks = [("start", time.time())]
    args, d = parse_args(argv)
    if args.realtime:
        raise_priority_for_realtime()
    out = d.out
    os.makedirs(out, exist_ok=True)
    run_dir = tempfile.mkdtemp(prefix="hil-")  # short: the control socket path must fit sun_path
    port = None if args.master else free_port()
    master_uri = args.master or "http://127.0.0.1:%d" % port
    env = flight_env(out, master_uri, run_dir)
    procs = Processes(env, out)
    gs_bind = args.vehicle_port or (14555 if d.external_gcs else free_port(socket.SOCK_DGRAM))
    gs_remote = args.gcs_port or (14550 if d.external_gcs else free_port(socket.SOCK_DGRAM))
    stop = {"now": False}

    def on_signal(sig, _frame):
        stop["now"] = True
    signal.signal(signal.SIGINT, on_signal)
    signal.signal(signal.SIGTERM, on_signal)
    code = 1
    status = "died"
    error = None
    try:
        if args.master:
            ros_master.reset_for_flight(master_uri)
        else:
            start_master(procs, port, master_uri, stop)
        marks.append(("master_up", time.time()))
        if not args.no_bag:
            procs.start("rosbag", ["rosbag", "record", "-O", os.path.join(out, "flight.bag"),
                                   "__name:=flight_recorder"] + BAG_TOPICS)
        launch = launch_command(args, d, run_dir, out, gs_bind, gs_remote)
        launcher = procs.start("launch", launch)
        marks.append(("launch_started", time.time()))
        try:
            done = wait_for_done(args, launcher, out, stop)
        except FlightTimeout:
            status = "timeout"
            raise
        marks.append(("done_seen", time.time()))
        if stop["now"]:
            print("run_flight: interrupted; stopping everything", file=sys.stderr)
            return 130
        with open(done) as f:
            code = int(f.read().strip() or 1)
    except RuntimeError as e:
        print("run_flight: %s" % e, file=sys.stderr)
        error = str(e)
        code = 1
    finally:
        procs.stop_all()
        for pid in leftovers(env[FLIGHT_VAR]):
            try:
                os.kill(pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
        if args.master:
            forget_flights_nodes(master_uri)
        shutil.rmtree(run_dir, ignore_errors=True)
        marks.append(("stopped", time.time()))
        with open(os.path.join(out, "run_flight_times.json"), "w") as f:
            json.dump(dict(marks), f)
    summary = os.path.join(out, "summary.json")
    if code != 0 or not os.path.exists(summary):
        return write_failed_summary(summary, out, args, d, status, error, code)
    with open(summary) as f:
        s = json.load(f)
    report(s, out, bag=not args.no_bag)
    if not args.no_bag:
        code = write_report(out, args.aircraft)
    return code


def build_pil_image(folder, aircraft, realtime=False):
    """The firmware for QEMU's mps2-an385 (make pil-image's script) with the aircraft's limits,
    built for this flight so the flight's folder holds the very image that flew; realtime: the
    board that keeps its own clock (pil_main.c, PIL_REALTIME)."""
    script = os.path.join(HERE, "..", "arduino_ha", "pil", "build_pil_image.sh")
    env = dict(os.environ, AIRCRAFT=aircraft)
    if realtime:
        env["PIL_CFLAGS"] = "-DPIL_REALTIME=1"
    r = subprocess.run(["bash", script, folder], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                       env=env)
    if r.returncode != 0:
        raise RuntimeError("the PIL image did not build: %s" % r.stdout.strip()[-2000:])
    return os.path.join(folder, "ha_pil.elf")


def write_report(out, aircraft):
    """The post-flight report of the flight's bag, by the same tool a real flight's log gets."""
    tool = os.path.join(HERE, "..", "drone_ros", "report", "scripts", "flight_report")
    folder = os.path.join(out, "report")
    r = subprocess.run([sys.executable, tool, os.path.join(out, "flight.bag"), "--out", folder,
                        "--aircraft", aircraft],
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if r.returncode != 0:
        print("run_flight: the report failed: %s" % r.stdout.strip(), file=sys.stderr)
        return r.returncode
    print("report: %s" % os.path.join(folder, "index.html"))
    return 0


def report(s, out, bag=True):
    tk = s.get("takeover") or {}
    print("flight: %s seed %d, %.0f s simulated in %.0f s (%.1fx real time)" % (
        s["aircraft"], s["seed"], s["simulated_s"], s["wall_s"], s["x_real_time"] or 0.0))
    for seg in s["who_flew"]:
        print("  %7.2f .. %7.2f s  %-10s %s" % (seg["from_s"], seg["to_s"], seg["controller"],
                                              " ".join(seg.get("why", [])) or ""))
    if tk:
        print("takeover: crash at %.2f s, HA at %s s (%s s after the deadline miss), HP back at %s s" % (
            tk["crash_injected_s"], tk["takeover_s"], tk["latency_after_deadline_miss_s"], tk["hand_back_s"]))
    m = s["margins"]
    print("margins: min height %.0f ft, ceiling margin %.0f ft, stall margin %.1f ft/s" % (
        m["min_height_above_home_ft"] or 0, m["min_ceiling_margin_ft"] or 0, m["min_stall_margin_ftps"] or 0))
    print("servo commands outside S_u: %d of %d steps; state while the HA flies: max S_x row %s" % (
        s["unsafe_servo_commands"]["outside_S_u"], s["unsafe_servo_commands"]["steps"],
        s["state_while_ha_flies"]["max_S_x_row"]))
    print("mission: %d of %d waypoints reached" % (s["mission"]["reached"], s["mission"]["waypoints"]))
    f, v = s["fault"], s["verdict"]
    print("fault: %s at %s s for %s s %s: %s" % (f["class"], f["at_s"], f["duration_s"], f["params"] or "",
                                                 "took effect" if f["took_effect"] else "DID NOT TAKE EFFECT"))
    print("  %s" % f["evidence"])
    print("verdict: %s (unsafe commands %d, %.2f s outside S_x under the HA, takeover latency %s s, "
          "recovery %s s%s), status %s" % ("ok" if v["ok"] else "PROPERTY BROKEN", v["unsafe_commands"],
                                            v["envelope_violations_under_ha_s"], v["takeover_latency_s"],
                                            v["recovery_s"], ", latched" if v["latched"] else "", s["status"]))
    beyond = (s.get("world") or {}).get("beyond_design_wind")
    if beyond:
        print("  beyond the design wind (a campaign judges it on survival): %s" % "; ".join(beyond))
    print("output: %s (%ssummary.json)" % (out, "flight.bag, report/, " if bag else ""))


if __name__ == "__main__":
    sys.exit(main())
