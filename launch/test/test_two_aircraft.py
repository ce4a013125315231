"""Two aircraft side by side on one ROS master: DG808_flight.launch twice, under <group ns="uav1">
and <group ns="uav2"> (launch/test/two_aircraft.launch), each with its own fake VN-200 on a pty
flying from its own place and its own home. Every topic an aircraft's nodes use must lie in its
namespace (or be one of the master's own: /rosout, /diagnostics, /tf, /tf_static), each
controller must read its own INS and only it, and each aircraft must have its own tf tree
(uavN/map -> uavN/odom -> uavN/base_link -> uavN/vn200), rooted at its own home.

Not two HiL flights: a lockstep HiL flight's simulator owns the master's one /clock
(use_sim_time is a global parameter too), so two would drive one clock back and forth; see
hil/README.md. With absolute topic names the two vn200 nodes would both publish /ins and each
controller would fly on both sensors: these checks fail then."""
import os
import socket
import time

import pytest

from launch_procs import echo, free_port, private_master, wait_for

os.environ.setdefault("MAVLINK20", "1")  # microhard_gs speaks MAVLink 2
from pymavlink import mavutil  # noqa: E402  (MAVLINK20 must be set first)

HERE = os.path.dirname(os.path.abspath(__file__))
AIRCRAFT = ("uav1", "uav2")
# Where each fake VN-200 starts (lat, lon in deg, alt in m), and so each aircraft's home: 11 km
# apart, so a reading from the other aircraft cannot pass for one's own.
ORIGIN = {"uav1": (45.4642, 9.1900, 150.0), "uav2": (45.5542, 9.3100, 210.0)}
# What an aircraft's namespace needs: every node of DG808_flight.launch (the fake sensor is no
# ROS node).
NODES = ["controller_DG808", "hp_supervisor", "vn200", "arduino", "microhard_gs"]
# The master's own topics, shared by design: the log, diagnostics (each status names its node)
# and tf (one tree per aircraft, told apart by the frame prefix).
SHARED = {"/rosout", "/diagnostics", "/tf", "/tf_static"}


@pytest.fixture(scope="module")
def fleet():
    with private_master("fleet_", "/fleet_test") as (master, env, run_dir, start):
        gs = {a: "%d %d" % (free_port(socket.SOCK_DGRAM), free_port(socket.SOCK_DGRAM)) for a in AIRCRAFT}
        start(["roslaunch", "--wait", os.path.join(HERE, "two_aircraft.launch"), "run_dir:=" + run_dir,
               "origin_uav1:=%s %s %s" % ORIGIN["uav1"], "origin_uav2:=%s %s %s" % ORIGIN["uav2"],
               "gs_ports_uav1:=" + gs["uav1"], "gs_ports_uav2:=" + gs["uav2"]])
        # Each aircraft's home, latched, as its `arduino` node keeps the HA's: map's origin.
        for a in AIRCRAFT:
            lat, lon, alt = ORIGIN[a]
            start(["rostopic", "pub", "-l", "/%s/home" % a, "drone_ros/HomePosition",
                   "{seq: 1, latitude: %r, longitude: %r, altitude: %r}" % (lat, lon, alt)])
        yield master, env, gs


def graph(master):
    """{node: set of topics it publishes or subscribes to}."""
    uses = {}
    pubs, subs, _ = master.getSystemState()
    for topic, nodes in list(pubs) + list(subs):
        for n in nodes:
            uses.setdefault(n, set()).add(topic)
    return uses


def test_each_aircraft_runs_every_node_in_its_namespace(fleet):
    master, _, _ = fleet
    wanted = ["/%s/%s" % (a, n) for a in AIRCRAFT for n in NODES]

    def missing():
        return [n for n in wanted if n not in graph(master)]
    assert wait_for(lambda: not missing()), "not up: %s" % missing()


def test_every_topic_of_an_aircraft_lies_in_its_namespace(fleet):
    master, _, _ = fleet
    wait_for(lambda: all("/%s/vn200" % a in graph(master) for a in AIRCRAFT))
    # The controller subscribes to everything it flies on: wait until it has.
    wait_for(lambda: all("/%s/ins" % a in graph(master).get("/%s/controller_DG808" % a, ())
                         for a in AIRCRAFT), 60.0)
    stray = {}
    for node, topics in graph(master).items():
        for a in AIRCRAFT:
            if node.startswith("/%s/" % a):
                out = sorted(t for t in topics if not t.startswith("/%s/" % a) and t not in SHARED)
                if out:
                    stray[node] = out
    assert stray == {}


def test_each_controller_reads_its_own_ins_and_only_it(fleet):
    master, env, _ = fleet
    for a in AIRCRAFT:
        other = [b for b in AIRCRAFT if b != a][0]

        def wired():
            pubs, subs, _ = master.getSystemState()
            return (dict(pubs).get("/%s/ins" % a) == ["/%s/vn200" % a]
                    and "/%s/controller_DG808" % a in dict(subs).get("/%s/ins" % a, []))
        assert wait_for(wired), "/%s/ins: %s" % (a, master.getSystemState()[:2])
        subs = dict(master.getSystemState()[1])
        assert "/%s/controller_DG808" % a not in subs.get("/%s/ins" % other, [])
        # What the controller flies on: its telemetry carries the last fix it read, which must be
        # its own sensor's every time (the other flies 11 km away).
        lat, lon, _ = ORIGIN[a]
        fixes = [(d["lla"]["x"], d["lla"]["y"]) for d in echo(env, "/%s/data" % a, 20)
                 if d["lla"]["x"] != 0.0]
        assert len(fixes) >= 10, fixes
        assert all(abs(x - lat) < 0.01 and abs(y - lon) < 0.01 for x, y in fixes), (a, fixes)


def test_each_aircraft_has_its_own_tf_tree_rooted_at_its_own_home(fleet):
    _, env, _ = fleet
    statics = {(t["header"]["frame_id"], t["child_frame_id"])
               for m in echo(env, "/tf_static", 2) for t in m["transforms"]}
    for a in AIRCRAFT:
        assert {(a + "/map", a + "/odom"), (a + "/base_link", a + "/vn200"),
                (a + "/vn200", a + "/vn200_frd")} <= statics, statics
    seen = {}
    deadline = time.time() + 60
    while set(seen) != set(AIRCRAFT) and time.time() < deadline:
        for m in echo(env, "/tf", 20):
            for t in m["transforms"]:
                assert "/" in t["child_frame_id"], "a frame of no aircraft: %s" % t["child_frame_id"]
                a = t["child_frame_id"].split("/")[0]
                seen[a] = t
    assert set(seen) == set(AIRCRAFT), seen
    for a, t in seen.items():
        assert (t["header"]["frame_id"], t["child_frame_id"]) == (a + "/odom", a + "/base_link")
        p = t["transform"]["translation"]
        # The fake flies north at about 1 m/s from its own home: near that home, not 11 km off.
        assert abs(p["x"]) < 1.0 and abs(p["z"]) < 1.0 and 0.0 <= p["y"] < 500.0, (a, p)
    for a in AIRCRAFT:
        odom = echo(env, "/%s/odom" % a, 1)[0]
        assert (odom["header"]["frame_id"], odom["child_frame_id"]) == (a + "/odom", a + "/base_link")


def test_each_aircraft_speaks_mavlink_as_its_own_system(fleet):
    """A ground station that sees both aircraft tells them apart by the MAVLink system id
    (DG808_flight.launch's gs_system_id): uav1 is system 1, uav2 system 2."""
    _, _, gs = fleet
    for system_id, a in enumerate(AIRCRAFT, start=1):
        remote_port = int(gs[a].split()[1])
        link = mavutil.mavlink_connection("udpin:127.0.0.1:%d" % remote_port, source_system=255)
        try:
            heartbeat = link.recv_match(type="HEARTBEAT", blocking=True, timeout=30)
        finally:
            link.close()
        assert heartbeat is not None, "%s: no HEARTBEAT on UDP %d" % (a, remote_port)
        assert heartbeat.get_srcSystem() == system_id, a
