"""The HiL simulator node: the physical world around the real HP nodes and the HA in the loop.

It steps the flight dynamics (hil.fdm), writes the VN-200's two serial ports (hil.sensors), feeds
the HA its clock and board inputs over the control channel (hil.ha_channel), applies the servo
outputs the HA drives, publishes the truth on /hil/truth, flies the scenario (mission upload as a
ground station, HP crash) and writes summary.json.

Lockstep (the default): the simulator owns time. Each step of the control period it
 1. writes the VN-200 packets due by then to both ports,
 2. waits until the `vn200` node has published them and the HA's /decision_status of the
    previous step has gone out (so every HP node has this step's inputs),
 3. publishes /clock,
 4. on the controller's periods waits for its /servo_op (bounded: a dead or hung HP shows as the
    wait running out, after which it is not waited for until it is back),
 5. steps the HA, which first takes that command from the real `arduino` node over its link,
 6. applies the servo outputs and advances the flight dynamics by one period.
Nothing advances while a participant has not answered, so the same seed gives the same flight:
the logged truth is identical bit for bit. When the HA asks for an HP restart, time stands until
hp_supervisor has started the controller again and it is connected (so its return does not
depend on how fast the machine is; in simulated time the restart takes no time).
"""
import io
import json
import math
import os
import select
import socket
import struct
import sys
import threading
import time
import warnings
import xmlrpc.client
from collections import deque

import rosgraph
import rospy
import yaml
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus, KeyValue
from drone_ros.msg import DecisionStatus, HilTruth, ServoCommand, hil_data, way
from sensor_msgs.msg import Temperature

from stack_tools.paths import ROOT  # noqa: E402  (aircraft/ of the source tree or the install)
from supervisor_core import node_query  # noqa: E402  (the supervisor's node queries: the same PID lookup)
from hil import faults, gs_monitor, ha_channel, link_relay, lockstep_io, mission, sensors, verdicts  # noqa: E402
from hil.faults.base import Board, rc_trimmed  # noqa: E402
from hil.aircraft_period import decision_rate_hz, design_airspeed_ftps  # noqa: E402
from hil.design_wind import DesignWind  # noqa: E402
from hil.flight_record import FlightRecord, Period, World  # noqa: E402
from hil.fdm import Fdm, FdmCrash, Surfaces, Wind  # noqa: E402
from stack_common import geo  # noqa: E402
from stack_common.rospy_shutdown import exit_promptly  # noqa: E402
from stack_common.units import FT_PER_M  # noqa: E402

# What the controller subscribes to (drone_ros/controller/README.md): connected before a step.
# Names relative to the flight's namespace, as every node of it uses them; resolved where the
# master's graph is asked (it knows only full names).
CONTROLLER_INPUTS = ["hil/lockstep", "ins", "attitude", "gps_position", "gps_velocity",
                     "imu_PQR_acceleration", "pwm", "decision_status", "way", "home"]


# What each step counts of what the vn200 and arduino nodes publish (hil.lockstep_io's keys),
# and the controller's commands: the topics this node subscribes to and waits for.
COUNTED = {"vn": "vn200/temperature", "status": "decision_status", "pwm": "pwm", "home": "home"}


def isa_temperature_c(elevation_ft):
    """ISA's temperature at an elevation in the troposphere: 15 C at sea level, 1.98 C per 1,000 ft."""
    return 15.0 - 0.0019812 * elevation_ft


class Waiter:
    """Counters fed by subscriber threads, waited on by the stepping thread. In lockstep the
    topics a step waits for are counted by the native node instead (hil.lockstep_io, `native`):
    its keys are asked there, the rest (the mission's /way) here."""

    def __init__(self, native=None):
        self.cond = threading.Condition()
        self.counts = {}
        self.latest = {}
        self.lost = {}
        self.silent_at = {}
        self.native = native
        self.native_keys = native.keys if native is not None else frozenset()

    def hit(self, key, msg=None):
        with self.cond:
            self.counts[key] = self.counts.get(key, 0) + 1
            self.latest[key] = msg
            self.cond.notify_all()

    def count(self, key):
        if key in self.native_keys:
            return self.native.count(key)
        with self.cond:
            return self.counts.get(key, 0)

    def latest_seq(self, key):
        """The seq of key's newest message (its first field, a uint32; None before the first)."""
        if key in self.native_keys:
            return self.native.latest_seq(key)
        with self.cond:
            m = self.latest.get(key)
        return None if m is None else m.seq

    def latest_of(self, key, msg_class):
        """The newest message of key (None before the first)."""
        if key in self.native_keys:
            return self.native.latest(key, msg_class)
        with self.cond:
            return self.latest.get(key)

    def wait_published(self, key, expected, timeout_s):
        """Waits until `expected` messages of `key` have arrived, less those given up on before.
        A message that never arrives (under heavy load one went out before the subscription was
        live) is waited for once, then counted as lost: otherwise the count stayed one short and
        every later step waited out the timeout. Returns how many were given up on now.

        A publisher that gave nothing in a whole timeout is silent: it is not waited for again
        until it publishes once more. Otherwise a dead node cost the timeout on every message it
        owed, and the flight never ended (campaign seed 26 #61: the vn200 node published nothing,
        and the simulator waited 10 s a packet)."""
        lost = self.lost.get(key, 0)
        silent = key in self.silent_at and self.count(key) == self.silent_at[key]
        if self.wait_count(key, expected - lost, 0.0 if silent else timeout_s):
            self.silent_at.pop(key, None)
            return 0
        self.silent_at[key] = self.count(key)
        self.lost[key] = expected - self.count(key)
        return self.lost[key] - lost

    def silent(self, key):
        """Whether the publisher of `key` is given up on until it publishes again."""
        return key in self.silent_at and self.count(key) == self.silent_at[key]

    def wait_count(self, key, at_least, timeout_s):
        deadline = time.monotonic() + timeout_s
        if key in self.native_keys:
            while True:  # in slices: a shutdown is seen within 0.1 s
                left = deadline - time.monotonic()
                if self.native.wait_count(key, at_least, min(max(left, 0.0), 0.1)):
                    return True
                if left <= 0.0 or rospy.is_shutdown():
                    return False
        with self.cond:
            while self.counts.get(key, 0) < at_least:
                left = deadline - time.monotonic()
                if left <= 0.0 or rospy.is_shutdown():
                    return False
                self.cond.wait(min(left, 0.1))
            return True


class LatencyProbe:
    """Real time: from a VN-200 packet written to the HP's port to the HA's servo output driven by
    the first HP command computed from it. Which packet a command came from, the controller says:
    its /to_hil record of the step carries the stamp of the /ins its GNC held (hil_data.ins_stamp),
    and the vn200 node stamps a packet's every topic alike, /vn200/temperature's included, so the
    stamp names the packet. (Before, the packet was the newest whose /vn200/temperature had reached
    this node before the command's stamp: a controller stepping on the packet computes its command
    before this Python node has taken the packet in, and was charged a period more.) The packet's
    write and the servo output are on the monotonic clock, the one ha_sil's micros() counts (its
    reply's t_us is the period's time). Only while the HP flies."""

    def __init__(self):
        self.lock = threading.Lock()
        self.written = {}     # packet index -> monotonic time written
        self.delivered = {}   # packet stamp (ns) -> packet index, in the order the node delivered
        self.n_delivered = 0
        self.used = {}        # command stamp (ns) -> stamp (ns) of the packet its step held
        self.commands = deque(maxlen=2000)  # (seq, command stamp ns) not yet seen by the HA
        self.applied = []     # (command stamp ns, monotonic time the HA's servos took it)

    def on_written(self, first, n):
        now = time.monotonic()
        with self.lock:
            for i in range(first, first + n):
                self.written[i] = now

    def on_delivered(self, msg):
        with self.lock:
            self.delivered.setdefault(msg.header.stamp.to_nsec(), self.n_delivered)
            self.n_delivered += 1

    def on_command(self, msg):
        with self.lock:
            self.commands.append((msg.seq, msg.stamp.to_nsec()))

    def on_record(self, msg):
        with self.lock:
            self.used[msg.header.stamp.to_nsec()] = msg.ins_stamp.to_nsec()

    def on_reply(self, reply, mono_now):
        # ha_sil's period time: CLOCK_MONOTONIC in microseconds, wrapped at 2^32.
        now_us = int(mono_now * 1e6)
        now = (now_us - ((now_us - reply.t_us) % (1 << 32))) * 1e-6
        with self.lock:
            # Commands the HA has seen (or, after an HP restart restarted the sequence, never will).
            while self.commands and (self.commands[0][0] <= reply.last_seq or
                                     self.commands[0][0] > reply.last_seq + 100000):
                seq, stamp = self.commands.popleft()
                if seq <= reply.last_seq and reply.controller == DecisionStatus.CONTROLLER_HP:
                    self.applied.append((stamp, now))

    def summary(self):
        with self.lock:
            first = {}  # packet index -> when the first command computed from it reached the servos
            for stamp, t in self.applied:
                i = self.delivered.get(self.used.get(stamp))
                if i is not None and i in self.written and (i not in first or t < first[i]):
                    first[i] = t
            lat = sorted(t - self.written[i] for i, t in first.items())
        if not lat:
            return None
        q = lambda f: round(lat[min(len(lat) - 1, int(f * len(lat)))] * 1000.0, 2)  # noqa: E731
        return {"packets": len(lat), "p50_ms": q(0.5), "p99_ms": q(0.99), "max_ms": round(lat[-1] * 1000.0, 2)}


class PhaseTimer:
    """Where each step's wall time goes."""

    def __init__(self):
        self.totals = {}
        self.t = time.perf_counter()

    def lap(self, name):
        now = time.perf_counter()
        self.totals[name] = self.totals.get(name, 0.0) + (now - self.t)
        self.t = now


class GraphLook:
    """One look at the ROS graph: the master's answers and each node's connections, each asked at
    most once, for the many checks of one poll (a restart's wait polls every 20 ms; asked check by
    check, one poll took some forty XML-RPC calls). Passed where a rosgraph.Master is."""

    def __init__(self, master):
        self.master, self.nodes, self.state, self.infos = master, {}, None, {}

    def lookupNode(self, name):  # noqa: N802  (rosgraph.Master's name)
        if name not in self.nodes:
            self.nodes[name] = self.master.lookupNode(name)
        return self.nodes[name]

    def getSystemState(self):  # noqa: N802
        if self.state is None:
            self.state = self.master.getSystemState()
        return self.state

    def bus_info(self, uri):
        if uri not in self.infos:
            self.infos[uri] = node_query.bus_info(uri, rospy.get_name())
        return self.infos[uri]


def bus_info(master, uri):
    """The node's getBusInfo connections (None: it does not answer), from the look if one is given."""
    return master.bus_info(uri) if isinstance(master, GraphLook) else node_query.bus_info(uri, rospy.get_name())


def node_pid(master, name):
    return node_query.node_pid(master, name, rospy.get_name())


def inbound_missing(master, name, topics):
    """Those of topics on which node `name` has no live inbound connection (all of them while
    the node does not answer)."""
    uri = node_query.node_uri(master, name)
    info = None if uri is None else bus_info(master, uri)
    if info is None:
        return list(topics)
    got = {c[4] for c in info if c[2] == "i" and (len(c) < 6 or c[5])}
    return [t for t in topics if t not in got]


def inbound_connected(master, name, topics):
    """Whether node `name` has a live inbound connection on each of topics."""
    return not inbound_missing(master, name, topics)


def publishers_of(master, topic):
    """The XML-RPC URIs of topic's registered publishers, from the master."""
    try:
        pubs, _, _ = master.getSystemState()
    except (rosgraph.MasterException, OSError):
        return []
    uris = []
    for t, nodes in pubs:
        if t == topic:
            for n in nodes:
                uri = node_query.node_uri(master, n)
                if uri is not None:
                    uris.append(uri)
    return uris


def reannounce_publishers(master, name, topic):
    """Tell node `name` the publishers of topic again, as the master does when one registers.
    roscpp asks a publisher for the topic once per announcement and never again if that call
    fails (a publisher too loaded to answer in time): a new announcement is its only retry."""
    uri = node_query.node_uri(master, name)
    pubs = publishers_of(master, topic)
    if uri is None or not pubs:
        return False
    try:
        code, _, _ = node_query.node_api(uri, 2.0).publisherUpdate("/master", topic, pubs)
    except (OSError, xmlrpc.client.Error):
        return False
    return code == 1


def publishers_serve(master, topic, subscriber):
    """Whether every publisher of topic lists node `subscriber` among its own outbound
    connections on it. A publisher lists a subscriber once their handshake is done, and only
    then is a message it publishes delivered there. The subscriber's own list is no proof:
    roscpp lists a publisher as soon as it starts to connect, and a restarted controller's first
    command could go out before the arduino node's connection was taken (HiL: the HA's wait for
    that command ran out, once in some fifteen crash flights)."""
    try:
        pubs, _, _ = master.getSystemState()
    except (rosgraph.MasterException, OSError):
        return False
    nodes = next((n for t, n in pubs if t == topic), [])
    for n in nodes:
        uri = node_query.node_uri(master, n)
        info = None if uri is None else bus_info(master, uri)
        if info is None or not any(c[2] == "o" and c[4] == topic and c[1] == subscriber for c in info):
            return False
    return True  # none yet (a mission's /way before its upload): nothing to go by


def clock_served(master):
    """Whether every node on simulated time (each subscriber of /clock) is served /clock by its
    publisher. A node that is not has a time of zero: the arduino node answered the HA's time
    requests with it, and the HA's reports of the first 9 s of a loaded flight were stamped 0.51 s."""
    try:
        _, subs, _ = master.getSystemState()
    except (rosgraph.MasterException, OSError):
        return False
    return all(publishers_serve(master, "/clock", n) for n in next((n for t, n in subs if t == "/clock"), []))


def publisher_connected(master, name, topic, publisher):
    """Whether node `name` has a live inbound connection on topic from node `publisher` (rospy
    names an inbound connection by the publisher's XML-RPC URI)."""
    uri, pub = node_query.node_uri(master, name), node_query.node_uri(master, publisher)
    info = None if uri is None or pub is None else bus_info(master, uri)
    if info is None:
        return False
    return any(c[2] == "i" and c[4] == topic and (len(c) < 6 or c[5]) and c[1].rstrip("/") == pub.rstrip("/")
                             for c in info)


class Simulation:
    """One HiL flight: the flight dynamics and the sensors stepped against every HP node and the
    HA, in lockstep or in real time, with one fault hosted. Made in four jobs, in this order:
    its configuration (the node's private parameters), its world (the aircraft's limits and
    airframe, the mission, the field's atmosphere), its ROS I/O (the publishers, the
    subscriptions and the step's bookkeeping) and its plant (the sensor ports, the HA's channel,
    the flight dynamics), then the fault it hosts."""

    def __init__(self):
        self._read_config()
        self._load_world()
        self._open_ros_io()
        self._open_plant()
        self._host_fault()

    @staticmethod
    def _param(key, default):
        return rospy.get_param("~" + key, default)

    def _read_config(self):
        """The node's private parameters, checked."""
        p = self._param
        self.aircraft = p("aircraft", "DG808")
        self.aircraft_dir = p("aircraft_dir", os.path.join(ROOT, "aircraft", self.aircraft))
        self.seed = int(p("seed", 1))
        self.mode = p("mode", "lockstep")
        if self.mode not in ("lockstep", "realtime"):
            raise RuntimeError("~mode must be lockstep or realtime, not %r" % self.mode)
        self.realtime = self.mode == "realtime"
        self.last_reply = None
        # The HA's rate: the aircraft's own unless the run asks for another (a benchmark at 20 Hz).
        self.rate_hz = float(p("rate_hz", 0.0)) or decision_rate_hz(self.aircraft_dir)
        self.controller_node = rospy.resolve_name(p("controller_node", "controller_" + self.aircraft))
        self.arduino_node = rospy.resolve_name("arduino")
        self.controller_inputs = [rospy.resolve_name(t) for t in CONTROLLER_INPUTS]
        self.servo_op_topic = rospy.resolve_name("servo_op")
        self.controller_dt_s = float(rospy.get_param(self.controller_node + "/dt", 0.05))
        self.reach_ft = float(rospy.get_param(self.controller_node + "/dist2b", 80.0))
        self.duration_s = float(p("duration_s", 240.0))
        # The fault (hil/faults): a class, when (negative: none), for how long (negative: to the
        # end), its parameters ("key=value key=value"). crash_at_s is the case study's name for when.
        self.crash_at_s = float(p("crash_at_s", 100.0))
        self.fault_name = p("fault", "crash")
        if self.fault_name not in faults.CLASSES + ("none",):
            raise RuntimeError("~fault must be one of %s or none, not %r" % (", ".join(faults.CLASSES), self.fault_name))
        self.fault_at_s = float(p("fault_at_s", self.crash_at_s))
        self.fault_duration_s = float(p("fault_duration_s", -1.0))
        self.fault_params = faults.parse_params(str(p("fault_params", "")).split())
        # Commands the HP corrupts pass through here: the arduino node then forwards
        # ~servo_relay_topic instead of servo_op (hil.launch's servo_relay).
        relay_topic = p("servo_relay_topic", "")
        self.relay_topic = rospy.resolve_name(relay_topic) if relay_topic else None
        self.ground_s = float(p("ground_s", 2.0))
        self.start_height_ft = float(p("start_height_ft", 200.0))
        # The aircraft's own cruise (a DG808's 60 ft/s start put the Aerosonde, which stalls at
        # 55, at its HA's stall switch from the first period).
        self.start_airspeed_ftps = float(p("start_airspeed_ftps", 0.0)) or design_airspeed_ftps(self.aircraft_dir)
        self.wait_s = float(p("wait_s", 10.0))
        self.restart_wait_s = float(p("restart_wait_s", 60.0))
        self.mission_file = p("mission", os.path.join(self.aircraft_dir, "missions", "case_study.waypoints"))
        self.out_dir = p("out_dir", "/tmp")
        self.wait_for_recorder = bool(p("wait_for_recorder", False))
        self.gs_port = int(p("gs_udp_port", 14555))
        # Where microhard_gs sends its telemetry, held as a ground station would (0: not held,
        # e.g. in real time, where QGroundControl holds it).
        self.gs_monitor_port = int(p("gs_monitor_port", 0))
        self.wind = Wind(float(p("wind_from_deg", 0.0)), float(p("wind_mps", 0.0)), p("turbulence", "none"))
        self.world_wind = self.wind  # the scenario's wind; a fault may change the FDM's in flight
        # The atmosphere of the field: its elevation (default, empty: the mission's home, where
        # the case study has always flown) and the day's temperature there (default, empty: ISA
        # at that elevation, 15 C at sea level). JSBSim's ISA with a temperature deviation is the
        # one atmosphere: the flight dynamics and the pitot (sensors.probe_airspeed_mps) both
        # take its density, so IAS and TAS differ as they do at that density altitude.
        fe, tc = str(p("field_elevation_ft", "")).strip(), str(p("temperature_c", "")).strip()
        self.field_elevation_ft = float(fe) if fe else None
        self.temperature_c = float(tc) if tc else None
        self.period_us = int(round(1e6 / self.rate_hz))
        self.controller_period_us = int(round(self.controller_dt_s * 1e6))

    def _load_world(self):
        """limits.yaml, the regions and the design wind of the aircraft, the mission, and the
        field's elevation and temperature."""
        with open(os.path.join(self.aircraft_dir, "limits.yaml")) as f:
            self.limits = yaml.safe_load(f)
        self.rc_trimmed = rc_trimmed(self.limits)
        self.regions = verdicts.Regions(self.limits)
        with open(os.path.join(self.aircraft_dir, "airframe.yaml")) as f:
            self.design_wind = DesignWind.load(self.limits, yaml.safe_load(f))
        self.plan = mission.read_wpl(self.mission_file)
        if self.field_elevation_ft is None:
            self.field_elevation_ft = self.plan.home[2] * FT_PER_M
        else:  # the same mission (its heights are above home) flown from a field that high
            self.plan = self.plan._replace(home=self.plan.home[:2] + (self.field_elevation_ft / FT_PER_M,))
        isa_c = isa_temperature_c(self.field_elevation_ft)
        if self.temperature_c is None:
            self.temperature_c = isa_c

    def _open_ros_io(self):
        """The publishers and subscriptions of the step loop, and its bookkeeping."""
        self.master = rosgraph.Master(rospy.get_name())
        # Lockstep: /clock, /hil/lockstep and the topics each step waits for, by the native node
        # (hil.lockstep_io), which publishes in this thread before it returns: "published" means
        # "on its way to every subscriber" in the stepping order. In real time nothing is waited
        # for, and the latency probe decodes what it reads: rospy subscriptions.
        self.counted = [rospy.resolve_name(t) for t in COUNTED.values()]
        self.io = None if self.realtime else lockstep_io.LockstepIo(
            dict(zip(COUNTED, self.counted), servo_op=self.servo_op_topic, to_hil=rospy.resolve_name("to_hil")))
        # The node whose connections the counted topics are: the preflight asks it.
        self.io_node = rospy.get_name() if self.io is None else self.io.name
        self.waiter = Waiter(self.io)
        # queue_size None: published in this thread before publish() returns.
        warnings.filterwarnings("ignore", message="The publisher should be created with an explicit keyword")
        self.truth_pub = rospy.Publisher("hil/truth", HilTruth, queue_size=None)
        # The master's one /diagnostics, as every node's: how fast the simulation goes, and in
        # real time whether it keeps up with the wall clock.
        self.diag_pub = rospy.Publisher("/diagnostics", DiagnosticArray, queue_size=10)
        self.late_steps = 0  # real time: steps that began more than a period after their time
        self.latency = LatencyProbe() if self.realtime else None
        # Real time: every period the HA ran on its own clock, from its replies: (time.monotonic()
        # of its tick, commands its link had delivered, controller, reasons at switch).
        # pace0_mono is the monotonic time of simulated 0 (verdicts.ha_periods puts the periods on
        # that axis). In lockstep the records are the HA's periods.
        self.ha_periods = [] if self.realtime else None
        self.pace0_mono = None
        if self.io is None:
            # Topics only counted are taken as bytes (rospy.AnyMsg); the latency probe reads the
            # VN-200 packets' and the commands' stamps, so those are decoded.
            rospy.Subscriber(COUNTED["vn"], Temperature, self.on_vn_delivered, queue_size=1000,
                             tcp_nodelay=True)
            rospy.Subscriber(COUNTED["status"], rospy.AnyMsg, lambda m: self.waiter.hit("status"), queue_size=1000,
                             tcp_nodelay=True)
            # The HA's own reports only: the arduino node's link-down /pwm (usbstatus 0) runs on the
            # wall clock. usbstatus is the message's last field, a byte.
            rospy.Subscriber(COUNTED["pwm"], rospy.AnyMsg, lambda m: m._buff[-1] and self.waiter.hit("pwm"),
                             queue_size=1000, tcp_nodelay=True)
            rospy.Subscriber("servo_op", ServoCommand, self.on_servo_op, queue_size=1000, tcp_nodelay=True)
            rospy.Subscriber(COUNTED["home"], rospy.AnyMsg, lambda m: self.waiter.hit("home"), queue_size=100,
                             tcp_nodelay=True)
        rospy.Subscriber("way", way, lambda m: self.waiter.hit("way", m), queue_size=10)
        if self.io is None:  # in lockstep the native node keeps the waypoint changes
            rospy.Subscriber("to_hil", hil_data, self.on_to_hil, queue_size=1000)
        self.relay_pub = None if self.relay_topic is None else \
            rospy.Publisher(self.relay_topic, ServoCommand, queue_size=None, tcp_nodelay=True)
        self.arduino_input = self.relay_topic or self.servo_op_topic
        # Who must have the controller's commands (with the relay, the arduino node takes the
        # relay's, which this node publishes).
        self.command_takers = [self.io_node] + ([] if self.relay_topic else [self.arduino_node])
        self.relayed = 0        # commands the HA's link must have delivered (relay)
        self.relayed_last = None
        self.relay_verified = False
        self.ha_commands = 0    # the HA's count of commands received, as of its last reply
        self.waypoint_log = []  # (t_s, waypoint_index) on change
        self.sim_t_s = 0.0

    def _open_plant(self):
        """The VN-200 ports, the HA's channel, the pitot and the battery, the flight dynamics,
        and the records the verdicts read."""
        p = self._param
        ports = {k: p(k, "") for k in ("hp_vn200_port", "ha_vn200_port", "ha_channel")}
        for k, v in ports.items():
            if not v:
                raise RuntimeError("~%s is required" % k)
            os.makedirs(os.path.dirname(v), exist_ok=True)
        os.makedirs(self.out_dir, exist_ok=True)
        # Every step's truth as /hil/truth serializes it (4-byte length, then the bytes): the bag
        # may drop messages when a loaded machine starves its recorder; this log never does.
        self.truth_log = open(os.path.join(self.out_dir, "truth.bin"), "wb")
        # One VN-200: both ports carry its one navigation solution, errors included.
        ins_errors = sensors.InsSolutionErrors(self.seed)
        self.ins_errors = ins_errors
        self.hp_vn = sensors.Vn200Port(ports["hp_vn200_port"], 2, self.seed, sensors.HP_VN200_BAUD,
                                       solution_errors=ins_errors)
        if self.latency is not None:
            self.hp_vn.on_written = self.latency.on_written
        self.ha_vn = sensors.Vn200Port(ports["ha_vn200_port"], 1, self.seed, sensors.HA_VN200_BAUD,
                                       fixed_output=sensors.HA_OUTPUT_1, solution_errors=ins_errors)
        self.chan = ha_channel.HaChannel(ports["ha_channel"])
        self.ams = sensors.Ams5812(self.seed)
        self.battery = sensors.Battery(self.seed)
        self.fdm = Fdm(self.aircraft_dir, self.seed, dt_s=1.0 / 200.0, wind=self.wind,
                       temperature_deviation_c=self.temperature_c - isa_temperature_c(self.field_elevation_ft))
        self.history = deque(maxlen=400)
        self.records = []
        self.events = []
        self.timer = PhaseTimer()
        self.hp_alive = True
        self.hp_pid = None
        self.status_expected = 0  # HA reports (a /decision_status and a /pwm each) the link carried
        self.hp_packets = 0
        self.home_expected = 0    # /home messages waited for: the one the HA sends as it latches home
        self.declared = (0, 0, 0, 0)  # self.delivered() as last declared on /hil/lockstep
        self.last_cmd_seq = None
        self.controller_index = -1
        self.progress_path = os.path.join(self.out_dir, "progress")

    def _host_fault(self):
        """The link relay and the ground-station monitor a fault or a flight needs, and the
        fault itself."""
        p = self._param
        # A man in the middle on the HP-HA link: the arduino node opens ~ha_link, ha_sil serves
        # ~ha_link_sil (hil.launch's link_relay).
        self.link_relay = None
        if p("ha_link_sil", ""):
            self.link_relay = link_relay.LinkRelay(p("ha_link", ""), p("ha_link_sil", ""))
        self.gs_monitor = None
        if self.gs_monitor_port:
            self.gs_monitor = gs_monitor.GsMonitor(self.gs_monitor_port, self.gs_port, lambda: self.sim_t_s)
        self.fault = None
        if self.fault_name != "none" and self.fault_at_s >= 0.0:
            if faults.needs_link_relay(self.fault_name) and self.link_relay is None:
                raise RuntimeError("fault %s needs the link relay (link_relay:=true)" % self.fault_name)
            if self.realtime and faults.needs_relay(self.fault_name):
                raise RuntimeError("fault %s corrupts the HP's commands: lockstep only" % self.fault_name)
            if faults.needs_relay(self.fault_name) and self.relay_pub is None:
                raise RuntimeError("fault %s needs the command relay (servo_relay:=true)" % self.fault_name)
            self.fault = faults.inject(self.fault_name, self, self.fault_at_s, self.fault_duration_s, self.fault_params)

    # --- callbacks -------------------------------------------------------------------------
    def on_vn_delivered(self, msg):
        if self.latency is not None:
            self.latency.on_delivered(msg)
        self.waiter.hit("vn")

    def on_servo_op(self, msg):
        if self.latency is not None:
            self.latency.on_command(msg)
        self.waiter.hit("servo_op", msg)

    def on_to_hil(self, msg):
        if self.latency is not None:
            self.latency.on_record(msg)
        if not self.waypoint_log or self.waypoint_log[-1][1] != msg.waypoint_index:
            self.waypoint_log.append((round(self.sim_t_s, 3), int(msg.waypoint_index)))

    # --- truth -----------------------------------------------------------------------------
    def record_truth(self, t_s):
        self.history.append((t_s, self.fdm.truth()))

    def truth_at(self, t_s):
        """The newest recorded truth at or before t_s (the oldest kept if none is). The history
        is in time order and the sensors ask for the last few entries: searched from the newest
        end, since walking all 400 from the oldest was the simulator's largest cost per step."""
        h = self.history
        for i in range(len(h) - 1, -1, -1):
            ts, tr = h[i]
            if ts <= t_s + 1e-9:
                return tr
        return h[0][1]

    def truth_since(self, t_s):
        """(t_s, HilTruth) of every step from t_s on."""
        return [(p.t_s, p.truth) for p in self.records if p.t_s >= t_s - 1e-9]

    def controller_pid(self):
        return node_pid(self.master, self.controller_node)

    def advance(self, duration_s):
        n = int(round(duration_s * 200.0))
        t0 = self.history[-1][0]
        for i in range(n):
            self.fdm.advance(1.0 / 200.0)
            self.record_truth(t0 + (i + 1) / 200.0)

    def event(self, t_s, what):
        self.events.append({"t_s": round(t_s, 3), "event": what})
        rospy.loginfo("hil_sim: t=%.2f s: %s", t_s, what)

    # --- participants ----------------------------------------------------------------------
    def controller_connected(self, graph=None):
        """The controller takes every input, the arduino node takes its commands, and so does this
        node: a restarted controller's first command would otherwise go by before this node's
        subscriber has connected to it, and the step would wait it out as an HP that is gone.
        graph: a GraphLook to ask (a new one by default)."""
        g = graph if graph is not None else GraphLook(self.master)
        return inbound_connected(g, self.controller_node, self.controller_inputs) and \
            inbound_connected(g, self.arduino_node, [self.arduino_input]) and \
            publisher_connected(g, self.io_node, self.servo_op_topic, self.controller_node) and \
            self.graph_served(self.controller_inputs, (), g)

    def graph_served(self, inputs, counted, graph=None):
        """Every publisher of the controller's inputs, of its commands and of what this node
        counts has taken its subscriber on (publishers_serve)."""
        g = graph if graph is not None else GraphLook(self.master)
        return all(publishers_serve(g, t, self.controller_node) for t in inputs) and \
            all(publishers_serve(g, self.servo_op_topic, n) for n in self.command_takers) and \
            all(publishers_serve(g, t, self.io_node) for t in counted)

    def service_while_waiting(self):
        self.hp_vn.service_commands()
        if self.realtime:
            replies = self.chan.pending_replies()
            self.note_ha_periods(replies, time.monotonic())
            self.last_reply = replies[-1] if replies else self.last_reply
            return self.last_reply or ha_channel.Reply(*([0, 0, (0.0,) * 4, (0.0,) * 4] + [0] * 15))
        return self.chan.poll()

    def idle(self, timeout_s):
        """Waits up to timeout_s, or until the vn200 node writes a command to answer."""
        select.select([self.hp_vn.pty.master], [], [], timeout_s)

    def wait_until(self, what, cond, timeout_s):
        deadline = time.monotonic() + timeout_s
        while not rospy.is_shutdown():
            reply = self.service_while_waiting()
            if cond(reply):
                return reply
            if time.monotonic() > deadline:
                raise RuntimeError("gave up waiting for " + what)
            self.idle(0.02)
        raise rospy.ROSInterruptException("shutdown")

    def wait_subscribed(self, wanted, timeout_s, reannounce_after_s=10.0):
        """Waits until each node of wanted {node: [topic, ...]} has a live inbound connection on
        each of its topics. A topic still missing after reannounce_after_s has its publishers
        announced to the node again (reannounce_publishers), once per period; past timeout_s the
        error names what is missing and who publishes it."""
        start = time.monotonic()
        last_announce = start
        while True:
            self.service_while_waiting()
            missing = {n: m for n, m in ((n, inbound_missing(self.master, n, t)) for n, t in wanted.items()) if m}
            if not missing:
                return
            now = time.monotonic()
            if rospy.is_shutdown():
                raise rospy.ROSInterruptException("shutdown")
            if now - start > timeout_s:
                raise RuntimeError("gave up waiting after %.0f s for subscriptions: %s" % (timeout_s, "; ".join(
                    "%s has no connection on %s" % (n, ", ".join(
                        "%s (publishers %s)" % (t, publishers_of(self.master, t) or "none") for t in m))
                    for n, m in missing.items())))
            if now - last_announce > reannounce_after_s:
                last_announce = now
                for n, topics in missing.items():
                    for t in topics:
                        done = reannounce_publishers(self.master, n, t)
                        rospy.logwarn("hil_sim: %s has no connection on %s after %.0f s: publishers announced "
                                      "again (%s)", n, t, now - start, "ok" if done else "failed")
            self.idle(0.02)

    def preflight(self):
        rospy.loginfo("hil_sim: waiting for ha_sil on %s", self.chan.path)
        deadline = time.monotonic() + 120.0
        # The vn200 node configures its sensor meanwhile: a command left unanswered here was
        # resent only after the node's 0.5 s response timeout.
        while not self.chan.accept(0.02):
            self.hp_vn.service_commands()
            if rospy.is_shutdown() or time.monotonic() > deadline:
                raise RuntimeError("ha_sil never connected to the control channel")
        if self.link_relay is not None:
            self.wait_until("ha_sil's link pty for the relay", lambda r: self.link_relay.connect(), 60.0)
        self.wait_until("the HA link (arduino node <-> ha_sil)", lambda r: r.flags & ha_channel.R_LINK_CONNECTED, 120.0)
        self.wait_until("the vn200 node's configuration of the VN-200", lambda r: self.hp_vn.configured(), 120.0)
        # no hil/lockstep on the wall clock
        inputs = self.controller_inputs[1:] if self.realtime else self.controller_inputs
        # This node counts what the vn200 and arduino nodes publish (the step waits for each VN-200
        # packet and HA report): a report sent before its own subscriber connected would leave the
        # count one short for the rest of the flight, every step waiting out wait_s.
        self.wait_subscribed({self.controller_node: inputs, self.arduino_node: [self.arduino_input],
                              self.io_node: self.counted}, 120.0)
        # Each of those connections taken by its publisher too (publishers_serve).
        self.wait_until("every publisher to take on the controller, the arduino node and this node as "
                        "subscribers", lambda r: self.graph_served(inputs, self.counted), 60.0)
        if not self.realtime:
            self.wait_until("every node on simulated time to be served /clock",
                            lambda r: clock_served(GraphLook(self.master)), 60.0)
        # With the relay, what reaches the HA must be what the relay sends, and nothing else.
        self.relay_verified = self.relay_topic is not None and \
            inbound_connected(self.master, self.arduino_node, [self.relay_topic]) and \
            not inbound_connected(self.master, self.arduino_node, [self.servo_op_topic])
        if self.relay_topic is not None and not self.relay_verified:
            raise RuntimeError("the arduino node does not take its commands from the relay %s only" % self.relay_topic)
        if self.wait_for_recorder:
            self.wait_until("the flight recorder", lambda r: self.truth_pub.get_num_connections() > 0, 60.0)
        for line in self.hp_vn.log:
            rospy.loginfo("hil_sim: VN-200 port 2: %s", line)
        self.hp_pid = node_pid(self.master, self.controller_node)

    # --- one step --------------------------------------------------------------------------
    def delivered(self):
        """What the controller's inputs have carried so far, in the order LockstepStep declares
        them: VN-200 packets, HA reports, homes, plans."""
        return self.hp_packets, self.status_expected, self.waiter.count("home"), self.waiter.count("way")

    def controller_steps_at(self, t_us):
        index = t_us // self.controller_period_us
        if index > self.controller_index:
            self.controller_index = index
            return True
        return False

    def step(self, k):
        t_us = k * self.period_us
        t_s = t_us * 1e-6
        self.sim_t_s = t_s
        tm = self.timer
        fault = self.fault
        if fault is not None:
            fault.on_step(t_s)
        tm.lap("scenario")
        self.emit_sensors(t_s)
        tm.lap("sensors")
        self.wait_hp_inputs(t_s)
        tm.lap("wait_hp_inputs")
        expect_command = self.controller_steps_at(t_us) and self.hp_alive
        want = self.waiter.count("servo_op") + 1  # counted before the clock moves: it may answer at once
        self.publish_step(t_us)
        # While the controller computes, on the other core: the navigation filter's errors for the
        # next step's packets, which do not depend on the flight (drawn in the same order, so
        # the same values; a third of the packets' cost, off the step's critical path).
        self.ins_errors.draw_until((t_us + self.period_us) * 1e-6)
        cmd_seq = None
        msg = None
        if expect_command:
            if self.waiter.wait_count("servo_op", want, self.wait_s):
                cmd_seq = self.waiter.latest_seq("servo_op")
                # Decoded only for a fault that reads it (it may corrupt or withhold it).
                msg = None if fault is None else self.waiter.latest_of("servo_op", ServoCommand)
            else:
                self.hp_alive = False
                self.event(t_s, "controller did not answer within %.1f s: not waited for until it is back" % self.wait_s)
        wait_count = False
        if fault is not None:
            out = fault.command(t_s, msg)
            if self.relay_pub is not None:
                for c in out:
                    self.relay_pub.publish(c)
                    self.relayed_last = c
                self.relayed = self.ha_commands + len(out)
                cmd_seq, wait_count = (self.relayed, True) if out else (None, False)
        tm.lap("wait_controller")
        tr = self.truth_at(t_s)
        board = self.board_inputs(t_s, tr)
        reply = self.chan.step(t_us, self.ha_vn.pty.written, cmd_seq, int(self.wait_s * 1000),
                               board.rc_pulses_us, board.rc_valid, board.airspeed_ftps, board.battery_v,
                               airspeed_ok=board.airspeed_ok, battery_ok=board.battery_ok, wait_count=wait_count)
        self.ha_commands = reply.commands_received
        if fault is not None:
            fault.after_step(t_s, reply)
        # The HA's share: the wall time it waited for the command to come through the arduino node.
        tm.totals["ha_step"] = tm.totals.get("ha_step", 0.0) - reply.wait_us * 1e-6
        tm.totals["ha_wait_command"] = tm.totals.get("ha_wait_command", 0.0) + reply.wait_us * 1e-6
        tm.lap("ha_step")
        if reply.flags & (ha_channel.R_COMMAND_TIMEOUT | ha_channel.R_VN_TIMEOUT):
            self.event(t_s, "ha_sil wait ran out (flags %#x)" % reply.flags)
        if reply.flags & ha_channel.R_LINK_CONNECTED:
            self.status_expected += 1
            # The period the HA latches home, it sends it: the next step waits for it, so the
            # controller takes home at a step the seed decides. Its repeats carry the same home
            # and are declared as they are seen.
            if reply.flags & ha_channel.R_HOME:
                self.home_expected = 1
        el, ai, ru, th = reply.applied
        self.fdm.set_surfaces(Surfaces(elevator_deg=el, aileron_deg=ai, rudder_deg=ru, throttle=th))
        self.publish_truth(t_us, tr, reply, cmd_seq)
        tm.lap("truth")
        if reply.flags & ha_channel.R_RESTART_REQUESTED:
            if reply.flags & ha_channel.R_LINK_CONNECTED:
                self.event(t_s, "HA requests an HP restart (restart %d)" % reply.restart_count)
                self.await_restart(t_s)
            else:
                # Over a link that is down (an HA just reset, its topics not yet negotiated
                # again) the request reaches no hp_supervisor: nothing to wait for.
                self.event(t_s, "HA requests an HP restart (restart %d) with its link down: no one on the HP "
                           "hears it, so none is waited for" % reply.restart_count)
        tm.lap("restart")
        return reply

    def wait_hp_inputs(self, t_s):
        """Until the vn200 node has published this step's packets and the arduino node the HA's
        last report (and home when it is due): what the step will declare to the controller."""
        for key, topic, expected in (("vn", "/vn200/temperature", self.hp_packets),
                                     ("status", "/decision_status", self.status_expected),
                                     ("pwm", "/pwm", self.status_expected),
                                     ("home", "/home", self.home_expected)):
            was_silent = self.waiter.silent(key)
            lost = self.waiter.wait_published(key, expected, self.wait_s)
            if lost and not was_silent:
                self.event(t_s, "%s late: %s %d of %d within %.1f s; %d counted as lost, not waited for again, "
                           "nor the node until it publishes" %
                           ("vn200 node" if key == "vn" else "arduino node", topic, self.waiter.count(key),
                            expected, self.wait_s, lost))

    def publish_step(self, t_us):
        """/clock moves to t_us, and /hil/lockstep declares the step: what this node has seen
        published since its last step, for the controller to wait for. Each VN-200 packet is one
        message on each of its five topics, each HA report one /decision_status and one /pwm;
        home and the plan as they went out."""
        now = self.delivered()
        packets, reports, homes, ways = (n - d for n, d in zip(now, self.declared))
        self.declared = now
        # LockstepStep's order: ins, attitude, gps_position, gps_velocity, imu_pqr_acceleration,
        # pwm, decision_status, home, way.
        self.io.publish_step(t_us, (packets,) * 5 + (reports, reports, homes, ways))
        # This node's own ROS time (main()).
        rospy.rostime._set_rostime(rospy.Time(t_us // 1000000, (t_us % 1000000) * 1000))

    def step_realtime(self, k):
        """Real time: nobody is waited for; the SIL runs its own periods on the wall clock and the
        latest servo outputs it reported are applied."""
        t_us = k * self.period_us
        t_s = t_us * 1e-6
        self.sim_t_s = t_s
        tm = self.timer
        if self.fault is not None:
            self.fault.on_step(t_s)
        tm.lap("scenario")
        self.emit_sensors(t_s)
        tm.lap("sensors")
        tr = self.truth_at(t_s)
        board = self.board_inputs(t_s, tr)
        self.chan.send_inputs(board.rc_pulses_us, board.rc_valid, board.airspeed_ftps, board.battery_v,
                              airspeed_ok=board.airspeed_ok, battery_ok=board.battery_ok)
        replies = self.chan.pending_replies()
        now = time.monotonic()
        self.note_ha_periods(replies, now)
        for r in replies:
            self.latency.on_reply(r, now)
        reply = replies[-1] if replies else None
        if reply is not None:
            self.last_reply = reply
            if self.fault is not None:
                self.fault.after_step(t_s, reply)
            if reply.flags & ha_channel.R_RESTART_REQUESTED:
                self.event(t_s, "HA requests an HP restart (restart %d)" % reply.restart_count)
        tm.lap("ha_step")
        if self.last_reply is None:
            return None
        el, ai, ru, th = self.last_reply.applied
        self.fdm.set_surfaces(Surfaces(elevator_deg=el, aileron_deg=ai, rudder_deg=ru, throttle=th))
        self.publish_truth(t_us, tr, self.last_reply, None)
        tm.lap("truth")
        return self.last_reply

    def note_ha_periods(self, replies, now_mono):
        """Real time: each reply is one period of the HA, stamped with its tick on its own clock:
        the SIL's micros() is CLOCK_MONOTONIC in microseconds (32 bits, wrapping), the clock of
        time.monotonic(), so the tick is dated exactly, not when this loop got round to it."""
        now_us = int(now_mono * 1e6)
        for r in replies:
            age_us = (now_us - r.t_us) & 0xFFFFFFFF
            if age_us >= 1 << 31:  # stamped a hair after now_mono was read
                age_us -= 1 << 32
            self.ha_periods.append((now_mono - age_us * 1e-6, r.commands_received, r.controller,
                                    r.reasons_at_switch))

    def publish_truth(self, t_us, tr, reply, cmd_seq):
        m = HilTruth()
        m.header.stamp = rospy.Time(t_us // 1000000, (t_us % 1000000) * 1000)
        m.header.frame_id = "map"
        m.latitude_deg, m.longitude_deg, m.altitude_msl_m = tr.lat_deg, tr.lon_deg, tr.alt_msl_m
        n_ft, e_ft = self.home_ref.north_east_ft(tr.lat_deg, tr.lon_deg)
        m.north_ft, m.east_ft = n_ft, e_ft
        m.height_above_home_ft = (tr.alt_msl_m - self.home[2]) * FT_PER_M
        m.roll_deg, m.pitch_deg, m.heading_deg = tr.roll_deg, tr.pitch_deg, tr.heading_deg
        m.p_deg_s, m.q_deg_s, m.r_deg_s = (math.degrees(v) for v in (tr.p_rad_s, tr.q_rad_s, tr.r_rad_s))
        m.accel_x_ft_s2, m.accel_y_ft_s2, m.accel_z_ft_s2 = (a * FT_PER_M for a in tr.accel_body_mps2)
        m.airspeed_ftps = tr.airspeed_true_mps * FT_PER_M
        m.groundspeed_ftps = math.hypot(tr.vn_mps, tr.ve_mps) * FT_PER_M
        m.alpha_deg, m.beta_deg = tr.alpha_deg, tr.beta_deg
        m.elevator_deg, m.aileron_deg = tr.servo.elevator_deg, tr.servo.aileron_deg
        m.rudder_deg, m.throttle = tr.servo.rudder_deg, tr.servo.throttle
        (m.ha_elevator_deg, m.ha_aileron_deg, m.ha_rudder_deg, m.ha_throttle) = reply.ha_command
        m.controller = reply.controller
        m.on_ground = bool(tr.on_ground)
        self.truth_pub.publish(m)
        buf = io.BytesIO()
        m.serialize(buf)
        self.truth_log.write(struct.pack("<I", buf.tell()) + buf.getvalue())
        self.records.append(Period(t_us, m, reply, cmd_seq, tr.airspeed_cal_mps * FT_PER_M))

    # --- faults and recovery ---------------------------------------------------------------
    def emit_sensors(self, t_s):
        """This period's VN-200 packets on both ports; a fault may keep a port silent (its packets
        are lost, not delayed)."""
        self.hp_vn.service_commands()
        f = self.fault
        if f is None or f.hp_vn_ok(t_s):
            self.hp_packets += self.hp_vn.emit_until(t_s, self.truth_at)
        else:
            self.hp_vn.skip_until(t_s)
        if f is None or f.ha_vn_ok(t_s):
            self.ha_vn.emit_until(t_s, self.truth_at)
        else:
            self.ha_vn.skip_until(t_s)

    def board_inputs(self, t_s, tr):
        """What the Due's board layer reads this period; a fault may change it."""
        b = Board(self.rc_trimmed, True, self.ams.read_ftps(sensors.probe_airspeed_mps(tr)), True,
                  self.battery.read_v(t_s, tr.servo.throttle), True)
        return b if self.fault is None else self.fault.board(t_s, b)

    def set_wind(self, t_s, wind):
        """The wind from now on (a fault's wind shift, gust front or shear; hil/faults/wind.py)."""
        self.fdm.set_wind(wind)
        self.wind = wind

    def await_restart(self, t_s):
        """Time stands until hp_supervisor has a new controller running and connected."""
        old = self.hp_pid
        t0 = time.monotonic()

        def back(_reply):
            g = GraphLook(self.master)
            pid = node_pid(g, self.controller_node)
            return pid is not None and pid != old and self.controller_connected(g)
        try:
            self.wait_until("hp_supervisor to restart the controller", back, self.restart_wait_s)
        except RuntimeError:
            self.event(t_s, "the controller did not come back within %.0f s" % self.restart_wait_s)
            return
        self.hp_pid = node_pid(self.master, self.controller_node)
        self.hp_alive = True
        self.controller_index = -1
        # What went out before the new controller subscribed never reaches it: not declared. Home
        # and the plan are latched: it has the last of each as it connects.
        packets, reports, homes, ways = self.delivered()
        self.declared = (packets, reports, homes - min(homes, 1), ways - min(ways, 1))
        self.event(t_s, "controller restarted by hp_supervisor (pid %d, %.2f s wall)" % (self.hp_pid, time.monotonic() - t0))

    # --- the flight ------------------------------------------------------------------------
    def run(self):
        home_lat, home_lon, ground_msl = self.plan.home
        wp1 = self.plan.items[0]
        heading = mission.bearing_deg(home_lat, home_lon, wp1.lat_deg, wp1.lon_deg)
        self.fdm.reset_on_ground(home_lat, home_lon, ground_msl, heading, held=True)
        self.record_truth(0.0)
        parked = self.fdm.truth()
        self.home = (home_lat, home_lon, parked.alt_msl_m)
        self.home_ref = geo.Ref(home_lat, home_lon)  # the truth's north and east, every step
        self.preflight()
        wall0 = time.monotonic()
        self.wall0_epoch = time.time()
        cpu0 = time.process_time()  # this process's CPU, its rospy threads included
        self.timer.t = time.perf_counter()
        steps = int(round(self.duration_s * self.rate_hz))
        ground_steps = int(round(self.ground_s * self.rate_hz))
        airborne = False
        last_progress = 0.0
        diag = (wall0, 0, 0)  # (wall time, step, late steps) at the last report
        k = 0
        try:
            for k in range(steps + 1):
                if rospy.is_shutdown():
                    break
                if k == ground_steps and not airborne:
                    self.upload_mission(k * self.period_us * 1e-6)
                    trim = self.fdm.reset_airborne(home_lat, home_lon, ground_msl,
                                                   self.start_height_ft / FT_PER_M, heading,
                                                   self.start_airspeed_ftps / FT_PER_M)
                    self.history.clear()
                    self.record_truth(k * self.period_us * 1e-6)
                    self.start_density_kg_m3 = self.fdm.truth().air_density_kg_m3
                    self.fdm.set_surfaces(trim)
                    airborne = True
                    self.event(k * self.period_us * 1e-6, "airborne start: %.0f ft above home, %.0f ft/s, heading %.0f deg" %
                               (self.start_height_ft, self.start_airspeed_ftps, heading))
                    self.timer.lap("mission_upload_and_trim")
                if self.realtime:
                    if k == 0 or k == ground_steps:
                        pace0 = time.monotonic() - k * self.period_us * 1e-6
                        self.pace0_mono = pace0
                    delay = pace0 + k * self.period_us * 1e-6 - time.monotonic()
                    if delay > 0.0:
                        time.sleep(delay)
                    elif delay < -self.period_us * 1e-6:
                        self.late_steps += 1
                    self.step_realtime(k)
                else:
                    self.step(k)
                self.timer.lap("step")
                if k < steps:
                    try:
                        self.advance(self.period_us * 1e-6)
                    except FdmCrash as crash:
                        self.event(k * self.period_us * 1e-6, "aircraft crashed: %s" % crash)
                        break
                self.timer.lap("fdm")
                now = time.monotonic()
                if now - last_progress > 0.5:
                    last_progress = now
                    self.write_progress(k * self.period_us * 1e-6)
                if now - diag[0] >= 1.0:
                    self.publish_diagnostics(k, now, diag)
                    diag = (now, k, self.late_steps)
        finally:
            self.wall_s = time.monotonic() - wall0
            self.cpu_s = time.process_time() - cpu0
            if self.io is not None:
                self.waypoint_log = self.io.waypoints()
            self.write_progress(k * self.period_us * 1e-6)

    def publish_diagnostics(self, k, now, since):
        """One status for the last wall second: the simulation's speed, and in real time the steps
        that started more than a period late (the HA and the HP then see sensor time slip)."""
        wall0, k0, late0 = since
        x_real = (k - k0) * self.period_us * 1e-6 / (now - wall0)
        late = self.late_steps - late0
        st = DiagnosticStatus(name="%s: simulation" % rospy.get_name().lstrip("/"), hardware_id="HiL simulator")
        if self.realtime and late > 0:
            st.level, st.message = DiagnosticStatus.WARN, "falling behind real time (%d late steps)" % late
        else:
            st.level, st.message = DiagnosticStatus.OK, "%s at %.1fx real time" % (self.mode, x_real)
        st.values = [KeyValue("simulated s", "%.2f" % (k * self.period_us * 1e-6)),
                     KeyValue("steps", str(k)), KeyValue("x real time", "%.2f" % x_real),
                     KeyValue("late steps", str(self.late_steps))]
        self.diag_pub.publish(DiagnosticArray(header=rospy.Header(stamp=rospy.Time.now()), status=[st]))

    def upload_mission(self, t_s):
        self.event(t_s, "uploading the mission (%d waypoints) through microhard_gs" % len(self.plan.items))
        before = self.waiter.count("way")
        result = None
        deadline = time.monotonic() + 60.0
        while time.monotonic() < deadline:
            self.service_while_waiting()
            result = mission.upload(self.plan, "127.0.0.1", self.gs_port, timeout_s=10.0)
            if result == "MAV_MISSION_ACCEPTED":
                break
            time.sleep(0.5)
        if result != "MAV_MISSION_ACCEPTED":
            raise RuntimeError("mission upload refused: %s" % result)
        self.wait_until("/way from microhard_gs", lambda r: self.waiter.count("way") > before, 30.0)
        # In lockstep the next step declares the plan and the controller waits for it. On the
        # wall clock the latched /way reaches it over its own connection: give it a moment.
        t_end = time.monotonic() + (0.5 if self.realtime else 0.0)
        while time.monotonic() < t_end:
            self.service_while_waiting()
            time.sleep(0.05)
        self.event(t_s, "mission accepted; /way has %d waypoints" % self.waiter.latest_of("way", way).fp)

    def write_progress(self, t_s):
        tmp = self.progress_path + ".tmp"
        with open(tmp, "w") as f:
            f.write("%.2f %.2f\n" % (t_s, self.duration_s))
        os.replace(tmp, self.progress_path)

    def flight_record(self):
        """The flight as its judges read it (hil.flight_record.FlightRecord)."""
        mon = self.gs_monitor
        return FlightRecord(
            aircraft=self.aircraft, seed=self.seed, mode=self.mode, rate_hz=self.rate_hz,
            period_us=self.period_us, controller_dt_s=self.controller_dt_s, periods=self.records,
            ha_periods=verdicts.ha_periods(self), ground_s=self.ground_s, regions=self.regions,
            stall_alphas_deg=verdicts.stall_alphas_deg(self.fdm.airframe), plan=self.plan,
            home=self.home, reach_ft=self.reach_ft, fault=self.fault,
            crashed_at=getattr(self, "crashed_at", None), events=self.events, waypoint_log=self.waypoint_log,
            world=World(self.field_elevation_ft, self.temperature_c, getattr(self, "start_density_kg_m3", None),
                        self.world_wind, self.wind, getattr(self, "design_wind", None)),
            gs_positions=None if mon is None else list(mon.positions), gs_home=None if mon is None else mon.home,
            wall_s=self.wall_s, cpu_s=getattr(self, "cpu_s", 0.0), step_totals=dict(self.timer.totals),
            latency=None if self.latency is None else self.latency.summary())

    def summary(self):
        return verdicts.summarize(self.flight_record())

    def close(self):
        self.truth_log.close()
        if self.gs_monitor is not None:
            self.gs_monitor.stop()
        for c in (self.chan, self.hp_vn, self.ha_vn) + ((self.link_relay,) if self.link_relay else ()):
            try:
                c.close()
            except OSError:
                pass
        self.fdm.close()

    def close_io(self):
        """The native node's goodbye: ros::shutdown unregisters its topics and waits for roscpp's
        XML-RPC thread, which works in slices of 0.1 s (0.12-0.23 s). main() says `done` first:
        nothing the flight wrote waits on it, and run_flight.py need not either."""
        if self.io is not None:
            self.io.close()
            self.io = None


def process_start_time():
    """When this process started (wall clock): its start in clock ticks after boot, from /proc."""
    with open("/proc/self/stat") as f:
        ticks = int(f.read().rsplit(")", 1)[1].split()[19])
    with open("/proc/stat") as f:
        boot = next(int(line.split()[1]) for line in f if line.startswith("btime "))
    return boot + ticks / os.sysconf("SC_CLK_TCK")


def main():
    # rospy's receive threads and this stepping thread share the GIL: a thread waiting on a
    # condition another thread has just set waits for the switch interval (5 ms by default).
    sys.setswitchinterval(1e-4)
    # Wall-clock marks of the simulator's phases (sim_times.json): run_flight.py's own
    # (run_flight_times.json) and these make the fixed cost of a flight that
    # hil/bench/bench_flight_overhead.py breaks down.
    marks = [("sim_started", process_start_time()), ("sim_imported", time.time())]
    # Its ROS time is the /clock it publishes, set as it publishes it (Simulation.publish_step),
    # not through a subscription to its own /clock: that one's thread took the GIL from the step
    # loop at every step to receive and decode a message this node had just sent.
    rospy.init_node("hil_sim", disable_rostime=True)
    exit_promptly()
    if rospy.get_param("/use_sim_time", False):
        rospy.rostime._set_rostime(rospy.Time(0, 0))  # as rospy's own /clock subscription starts it
    marks.append(("node_up", time.time()))
    sim = Simulation()
    marks.append(("sim_set_up", time.time()))
    code = 0
    try:
        sim.run()
        marks += [("preflight_done", sim.wall0_epoch), ("flight_done", time.time())]
        summary = sim.summary()
        path = os.path.join(sim.out_dir, "summary.json")
        with open(path, "w") as f:
            json.dump(summary, f, indent=2)
        marks.append(("summary_written", time.time()))
        with open(os.path.join(sim.out_dir, "sim_times.json"), "w") as f:
            json.dump(dict(marks), f)
        rospy.loginfo("hil_sim: summary in %s", path)
    except (RuntimeError, ConnectionError, socket.timeout) as e:
        rospy.logfatal("hil_sim: %s", e)
        with open(os.path.join(sim.out_dir, "error.txt"), "w") as f:
            f.write(str(e) + "\n")
        code = 1
    except Exception as e:  # a bug here: the flight still ends with its reason, not "done 0" and no summary
        import traceback
        rospy.logfatal("hil_sim: %s", traceback.format_exc())
        with open(os.path.join(sim.out_dir, "error.txt"), "w") as f:
            f.write("the simulator failed: %s: %s\n" % (type(e).__name__, e))
        code = 1
    finally:
        sim.close()
        # Atomic: run_flight.py reads it as soon as the name exists, and an empty file read
        # mid-write counted as a failed flight (and its summary was overwritten).
        done = os.path.join(sim.out_dir, "done")
        with open(done + ".tmp", "w") as f:
            f.write("%d\n" % code)
        os.replace(done + ".tmp", done)
        sim.close_io()
    return code


if __name__ == "__main__":
    sys.exit(main())
