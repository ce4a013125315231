"""Shared machinery of the microhard_gs Python tests and benchmark (a helper, not a test).

Starts a private ROS master on a free port, loads the aircraft's own controller parameters
(aircraft/DG808/controller_param.yaml and limits.yaml, where DG808_flight.launch puts them),
launches microhard_gs with its launch file, optionally the real controller_DG808 (which answers
PARAM_SETs through its ~set_tunable), runs gs_ros_probe.py as the stand-in for the rest of the
aircraft, and gives the test a pymavlink connection: the real ground-station client, over UDP on
127.0.0.1 only. Every process started here is stopped by stop().
"""
import json
import os
import queue
import random
import signal
import socket
import struct
import subprocess
import sys
import threading
import time

import rosgraph
import rosparam

os.environ.setdefault("MAVLINK20", "1")
from pymavlink import mavutil  # noqa: E402  (MAVLINK20 must be set first)

from stack_tools import ports  # noqa: E402
from stack_tools.paths import ROOT  # noqa: E402

HERE = os.path.join(ROOT, "microhard_gs", "test")  # gs_ros_probe.py
AIRCRAFT_DIR = os.path.join(ROOT, "aircraft", "DG808")
CONTROLLER_NS = "/controller_DG808"
HOME = (40.1100, -88.2200, 220.0)  # where the probe says the aircraft is: becomes home
ROS_PYTHON = sys.executable  # the test's own Python (cmake/python.cmake)
FT_PER_M = 1.0 / 0.3048
DIAGNOSTIC_PERIOD_S = 0.1

mavlink = mavutil.mavlink


def free_port(kind=socket.SOCK_DGRAM):
    return ports.free_port(kind)


def stop_process_groups(procs):
    """Ctrl-C to each process group still running, then wait; SIGKILL what outlives 10 s."""
    procs = list(procs)
    for p in procs:
        if p.poll() is None:
            try:
                os.killpg(p.pid, signal.SIGINT)
            except ProcessLookupError:
                pass
    for p in procs:
        try:
            p.wait(timeout=10)
        except subprocess.TimeoutExpired:
            os.killpg(p.pid, signal.SIGKILL)
            p.wait(timeout=5)


def _state(proc):
    return "running" if proc.poll() is None else "ended with %s" % proc.returncode


def _tail(path, lines=30):
    try:
        with open(path, "rb") as f:
            return b"".join(f.readlines()[-lines:]).decode(errors="replace")
    except OSError as e:
        return "(unreadable: %s)" % e


class LossyRelay:
    """Forwards datagrams between the GCS and the node, dropping a fraction each way."""

    def __init__(self, node_port, gcs_port, loss, seed=7):
        self.node_addr = ("127.0.0.1", node_port)
        self.gcs_addr = ("127.0.0.1", gcs_port)
        self.loss = loss
        self.rng = random.Random(seed)
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.sock.bind(("127.0.0.1", 0))
        self.sock.settimeout(0.1)
        self.port = self.sock.getsockname()[1]
        self.forwarded = 0
        self.dropped = 0
        self._stop = False
        self._thread = threading.Thread(target=self._run, daemon=True)
        self._thread.start()

    def _run(self):
        while not self._stop:
            try:
                payload, addr = self.sock.recvfrom(4096)
            except socket.timeout:
                continue
            except OSError:
                return
            if self.rng.random() < self.loss:
                self.dropped += 1
                continue
            self.forwarded += 1
            target = self.gcs_addr if addr == self.node_addr else self.node_addr
            self.sock.sendto(payload, target)

    def stop(self):
        self._stop = True
        self._thread.join(timeout=2)
        self.sock.close()


class GsSystem:
    def __init__(self, launch_args=None, relay_loss=None, probe_rate_hz=20.0, udp_client=True, controller=False,
                 node=True):
        self.procs = []
        self.launch = None
        self.events = queue.Queue()
        self.diagnostics = {}
        self.relay = None
        self.conn = None
        ws = os.environ.get("DRONE_ROS_WS")
        if not ws:
            raise RuntimeError("DRONE_ROS_WS must point at the built catkin workspace")
        self.env = dict(os.environ)
        self.master_port = free_port(socket.SOCK_STREAM)
        self.env["ROS_MASTER_URI"] = "http://127.0.0.1:%d" % self.master_port
        self.env["ROS_IP"] = "127.0.0.1"
        self.env.pop("ROS_HOSTNAME", None)
        self.env["ROS_LOG_DIR"] = os.environ.get("ROS_LOG_DIR", "/tmp/microhard_gs_test_logs")
        self.node_port = free_port()
        self.gcs_port = free_port()
        remote_port = self.gcs_port
        try:
            if relay_loss is not None:
                self.relay = LossyRelay(self.node_port, self.gcs_port, relay_loss)
                remote_port = self.relay.port
            master = self._start(["rosmaster", "--core", "-p", str(self.master_port)])
            self.master = rosgraph.Master("/gs_harness", master_uri=self.env["ROS_MASTER_URI"])
            self._wait_for_master(master)
            # As `rosparam load FILE NS` does it (rosparam's own reader, then one set per key),
            # in this process rather than two more interpreters.
            self._load_params(os.path.join(AIRCRAFT_DIR, "controller_param.yaml"), CONTROLLER_NS)
            self._load_params(os.path.join(AIRCRAFT_DIR, "limits.yaml"), CONTROLLER_NS + "/limits")
            if controller:
                self._start([os.path.join(ws, "devel", "lib", "drone_ros", "controller_DG808"),
                             "__name:=controller_DG808"])
                self._wait_for_service(CONTROLLER_NS + "/set_tunable")
            if udp_client:
                # Bound before the node starts, as a ground station already listening: the node's
                # first HEARTBEAT waits in the socket instead of going to a closed port.
                self.conn = mavutil.mavlink_connection("udpin:127.0.0.1:%d" % self.gcs_port,
                                                       source_system=255, source_component=190,
                                                       dialect="development")
            self.remote_port = remote_port
            self.probe = self._start([ROS_PYTHON, os.path.join(HERE, "gs_ros_probe.py"),
                                      "--lat", str(HOME[0]), "--lon", str(HOME[1]), "--alt", str(HOME[2]),
                                      "--rate", str(probe_rate_hz)],
                                     stdin=subprocess.PIPE, stdout=subprocess.PIPE)
            threading.Thread(target=self._read_probe, daemon=True).start()
            if not node:  # the test starts and stops microhard_gs itself (start_node, stop_node)
                return
            self.start_node(launch_args)
            if not udp_client:  # the test talks over another link (the serial transport)
                return
            hb = self.conn.wait_heartbeat(timeout=30)
            if hb is None:
                raise RuntimeError("no HEARTBEAT from microhard_gs")
        except Exception:
            self.stop()
            raise

    def start_node(self, launch_args=None):
        """microhard_gs through its launch file; returns once it and the probe are connected."""
        args = {"udp_bind_address": "127.0.0.1", "udp_bind_port": self.node_port,
                "udp_remote_address": "127.0.0.1", "udp_remote_port": self.remote_port,
                # Diagnostics at 10 Hz instead of the node's 1 Hz: a test waiting for a
                # counter sees it within 0.1 s of the change, and reads the same values.
                "diagnostic_period_s": DIAGNOSTIC_PERIOD_S}
        args.update(launch_args or {})
        self.launch = self._start(["roslaunch", "drone_ros", "microhard_gs.launch"] +
                                  ["%s:=%s" % kv for kv in args.items()])
        waiting = {"missing": "no report from the probe"}
        deadline = time.time() + 60
        while time.time() < deadline and self.launch.poll() is None and self.probe.poll() is None:
            event = self.wait_event(lambda e: e["topic"] in ("connected", "waiting"), 1.0)
            if event is not None and event["topic"] == "connected":
                return
            waiting = event or waiting
        raise RuntimeError("microhard_gs and the probe never connected on ROS: %s" % self._why_not_connected(waiting))

    def _why_not_connected(self, waiting):
        """What a test that gave up on the connection reports: which process ended, which of the
        node's topics never reached the probe, and the last lines each of them logged."""
        parts = ["roslaunch %s, probe %s; the probe still missed %s" % (
            _state(self.launch), _state(self.probe), waiting["missing"])]
        for p in (self.launch, self.probe):
            parts.append("--- last lines of %s:\n%s" % (p.log_path, _tail(p.log_path)))
        return "\n".join(parts)

    def stop_node(self):
        """Stops the launch start_node made, and waits until the probe has lost it: every event
        of that node is then behind the test, none is read as the next node's."""
        launch, self.launch = self.launch, None
        stop_process_groups([launch])
        self.procs.remove(launch)
        if self.wait_event(lambda e: e["topic"] == "disconnected", 30) is None:
            raise RuntimeError("the probe never saw microhard_gs go")

    def _start(self, cmd, **kw):
        os.makedirs(self.env["ROS_LOG_DIR"], exist_ok=True)
        name = os.path.basename(cmd[1] if cmd[0] == ROS_PYTHON else cmd[0])
        log_path = os.path.join(self.env["ROS_LOG_DIR"], "%s-%d.log" % (name, self.master_port))
        log = open(log_path, "ab")
        kw.setdefault("stdout", log)
        p = subprocess.Popen(cmd, env=self.env, start_new_session=True, stderr=log, **kw)
        p.log_path = log_path
        log.close()
        self.procs.append(p)
        return p

    def _wait_for_master(self, proc):
        deadline = time.time() + 20
        while time.time() < deadline and proc.poll() is None:
            try:
                pid = self.master.getPid()
            except OSError:
                time.sleep(0.05)
                continue
            if pid != proc.pid:  # our pick of a free port was another test's pick too
                raise RuntimeError("port %d answers as the master of pid %d, not ours (%d)" %
                                   (self.master_port, pid, proc.pid))
            return
        raise RuntimeError("rosmaster did not start (%s):\n%s" % (_state(proc), _tail(proc.log_path)))

    def _load_params(self, path, namespace):
        for params, ns in rosparam.load_file(path, default_namespace=namespace):
            self._set_param(ns, params)

    def _set_param(self, name, value):
        if isinstance(value, dict):  # rosparam's update, key by key
            for key, item in value.items():
                self._set_param(rosgraph.names.ns_join(name, key), item)
        else:
            self.master.setParam(name, value)

    def _wait_for_service(self, name, timeout=30.0):
        deadline = time.time() + timeout
        while time.time() < deadline:
            try:
                self.master.lookupService(name)
                return
            except rosgraph.MasterError:  # not registered yet
                time.sleep(0.05)
        raise RuntimeError("%s never appeared" % name)

    def rosparam(self, name):
        out = subprocess.run(["rosparam", "get", name], env=self.env, capture_output=True, text=True, timeout=30)
        return out.stdout.strip()

    def _read_probe(self):
        for line in self.probe.stdout:
            try:
                event = json.loads(line)
            except ValueError:
                continue
            if event.get("topic") == "diagnostics":
                self.diagnostics = event["values"]
            self.events.put(event)

    def wait_event(self, predicate, timeout):
        deadline = time.time() + timeout
        while time.time() < deadline:
            try:
                event = self.events.get(timeout=max(0.01, deadline - time.time()))
            except queue.Empty:
                break
            if predicate(event):
                return event
        return None

    def drain_events(self):
        out = []
        while True:
            try:
                out.append(self.events.get_nowait())
            except queue.Empty:
                return out

    def send_decision(self, controller, reasons, altitude_agl_ft=0.0):
        self.probe.stdin.write(("decision %d %d %f\n" % (controller, reasons, altitude_agl_ft)).encode())
        self.probe.stdin.flush()

    def decision_reached_node(self, controller, altitude_agl_ft=0.0, timeout=30.0):
        """Waits until microhard_gs's diagnostics show this decision status as the last it heard.
        Diagnostics arrive in the order they went out, so once a status has shown, no later wait
        can be fooled by an older one; callers wait for each status they send before the next."""
        def heard(values):
            return (values.get("decision_controller") == str(controller) and
                    values.get("decision_altitude_agl_ft") not in (None, "none") and
                    float(values["decision_altitude_agl_ft"]) == float(altitude_agl_ft))
        return self.wait_event(lambda e: e["topic"] == "diagnostics" and heard(e["values"]), timeout) is not None

    def diagnostic(self, key, timeout=5.0):
        """Waits for a fresh diagnostics message and returns one of its values."""
        event = self.wait_event(lambda e: e["topic"] == "diagnostics", timeout)
        return None if event is None else event["values"].get(key)

    def wait_diagnostic(self, key, predicate, timeout=30.0):
        """Fresh diagnostics until the value of key meets predicate; returns the last value seen
        (None if none came), so the caller's assertion shows what it was."""
        deadline = time.time() + timeout
        value = None
        while time.time() < deadline:
            value = self.diagnostic(key, timeout=max(0.1, deadline - time.time()))
            if value is not None and predicate(value):
                return value
        return value

    def stop(self):
        if self.conn is not None:
            self.conn.close()
            self.conn = None
        stop_process_groups(reversed(self.procs))
        self.procs = []
        if self.relay is not None:
            self.relay.stop()
            self.relay = None


# --------------------------------------------------------------------------- MAVLink client side

def local_to_latlon(north_ft, east_ft):
    """Inverse of the node's flat-earth projection, for building test missions (ft -> deg)."""
    import math
    a, e2 = 6378137.0, 6.69437999014e-3
    lat0 = math.radians(HOME[0])
    w2 = 1 - e2 * math.sin(lat0) ** 2
    r_n = a * (1 - e2) / (w2 * math.sqrt(w2))
    r_e = a / math.sqrt(w2)
    lat = HOME[0] + math.degrees(north_ft / FT_PER_M / r_n)
    lon = HOME[1] + math.degrees(east_ft / FT_PER_M / (r_e * math.cos(lat0)))
    return lat, lon


ABSOLUTE_FRAMES = (mavlink.MAV_FRAME_GLOBAL, mavlink.MAV_FRAME_GLOBAL_INT)


def waypoint(seq, north_ft, east_ft, height_ft, frame=mavlink.MAV_FRAME_GLOBAL_RELATIVE_ALT_INT):
    """A waypoint `height_ft` above home; in an absolute (MSL) frame its altitude is home's plus that."""
    lat, lon = local_to_latlon(north_ft, east_ft)
    z_m = height_ft / FT_PER_M + (HOME[2] if frame in ABSOLUTE_FRAMES else 0.0)
    return mavlink.MAVLink_mission_item_int_message(
        1, 1, seq, frame, mavlink.MAV_CMD_NAV_WAYPOINT, 0, 1,
        0, 10, 0, float("nan"), int(round(lat * 1e7)), int(round(lon * 1e7)), z_m,
        mavlink.MAV_MISSION_TYPE_MISSION)


def as_legacy(item):
    """The same item as a legacy MISSION_ITEM (degrees), in the same frame."""
    return mavlink.MAVLink_mission_item_message(
        item.target_system, item.target_component, item.seq, item.frame,
        item.command, item.current, item.autocontinue, item.param1, item.param2, item.param3, item.param4,
        item.x * 1e-7, item.y * 1e-7, item.z, item.mission_type)


def upload_mission(conn, items, count=None, resend_s=1.0, timeout_s=30.0, legacy=False):
    """Uploads like QGroundControl: send the count, answer each request, resend on silence.
    Returns the MISSION_ACK (None if none came)."""
    count = len(items) if count is None else count
    conn.mav.mission_count_send(1, 1, count, mavlink.MAV_MISSION_TYPE_MISSION)
    deadline = time.time() + timeout_s
    last_activity = time.time()
    last_sent = None
    while time.time() < deadline:
        msg = conn.recv_match(type=["MISSION_REQUEST_INT", "MISSION_REQUEST", "MISSION_ACK"],
                              blocking=True, timeout=0.1)
        if msg is None:
            if time.time() - last_activity > resend_s:
                if last_sent is None:
                    conn.mav.mission_count_send(1, 1, count, mavlink.MAV_MISSION_TYPE_MISSION)
                else:
                    conn.mav.send(last_sent)
                last_activity = time.time()
            continue
        if msg.get_type() == "MISSION_ACK":
            return msg
        last_activity = time.time()
        if msg.seq < len(items):
            item = items[msg.seq]
            last_sent = as_legacy(item) if legacy else item
            conn.mav.send(last_sent)
    return None


def download_mission(conn, timeout_s=10.0, attempts=1, legacy=False, gave_up=None):
    """Downloads like QGroundControl: every request is repeated on silence, `attempts` times.
    legacy: ask with MISSION_REQUEST and get MISSION_ITEMs. On failure returns None and appends
    to `gave_up` (a list, if given) what it was waiting for."""
    def ask(send, kind, match=lambda m: True, what=None):
        for _ in range(attempts):
            send()
            deadline = time.time() + timeout_s
            while time.time() < deadline:
                m = conn.recv_match(type=kind, blocking=True, timeout=0.1)
                if m is not None and match(m):
                    return m
        if gave_up is not None:
            gave_up.append(what or kind)
        return None

    count_msg = ask(lambda: conn.mav.mission_request_list_send(1, 1, mavlink.MAV_MISSION_TYPE_MISSION),
                    "MISSION_COUNT")
    if count_msg is None:
        return None
    items = []
    for seq in range(count_msg.count):
        if legacy:
            item = ask(lambda: conn.mav.mission_request_send(1, 1, seq, mavlink.MAV_MISSION_TYPE_MISSION),
                       "MISSION_ITEM", lambda m: m.seq == seq, "MISSION_ITEM %d" % seq)
        else:
            item = ask(lambda: conn.mav.mission_request_int_send(1, 1, seq, mavlink.MAV_MISSION_TYPE_MISSION),
                       "MISSION_ITEM_INT", lambda m: m.seq == seq, "MISSION_ITEM_INT %d" % seq)
        if item is None:
            return None
        items.append(item)
    conn.mav.mission_ack_send(1, 1, mavlink.MAV_MISSION_ACCEPTED, mavlink.MAV_MISSION_TYPE_MISSION)
    return items


def command_long(conn, command, *params):
    p = list(params) + [0.0] * (7 - len(params))
    conn.mav.command_long_send(1, 1, command, 0, *p)


def wait_for_message(conn, kind, matches, timeout_s=5.0):
    """The next message of kind for which matches(message) holds, or None after timeout_s."""
    deadline = time.time() + timeout_s
    while time.time() < deadline:
        m = conn.recv_match(type=kind, blocking=True, timeout=0.2)
        if m is not None and matches(m):
            return m
    return None


def wait_command_ack(conn, command, timeout_s=5.0):
    return wait_for_message(conn, "COMMAND_ACK", lambda m: m.command == command, timeout_s)


def wait_param_value(conn, param_id, timeout_s=5.0):
    """The next PARAM_VALUE for param_id (the echo of a PARAM_SET), decoded byte-wise if INT32."""
    return wait_for_message(conn, "PARAM_VALUE", lambda m: m.param_id == param_id, timeout_s)


def param_value(m):
    if m.param_type == mavlink.MAV_PARAM_TYPE_INT32:
        return struct.unpack("<i", struct.pack("<f", m.param_value))[0]
    return m.param_value


def wait_statustext(conn, needle, timeout_s=5.0):
    deadline = time.time() + timeout_s
    while time.time() < deadline:
        st = conn.recv_match(type="STATUSTEXT", blocking=True, timeout=0.2)
        if st is not None and needle in st.text:
            return st
    return None
