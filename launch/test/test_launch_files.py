"""Every launch file started as a user starts it, in HiL configuration on one ROS master:
DG808_hil.launch (which is DG808_flight.launch with its ports on ptys, and through it the
hp_supervisor, vn200, arduino and microhard_gs launch files), view.launch (the markers; rviz itself
needs a display: rviz:=false) and record.launch. The expected nodes come up, every topic the
stack's interfaces name has a publisher and carries messages, the recorder writes its log under
the dated name; then everything started here is stopped."""
import glob
import os
import socket
import subprocess
import time

import pytest
import yaml

from launch_procs import echo, free_port, private_master, stop, wait_for

# ha_sil is no ROS node (the HA speaks rosserial over its pty, as the Due does): /decision_status
# flowing from the arduino node below is what shows it up.
# The simulator's process holds two nodes in lockstep: hil_sim and hil_sim_io, the roscpp node of
# its per-step I/O (/clock, /hil/lockstep; hil/HIL_INTERFACES.md, section 3).
NODES = ["/controller_DG808", "/hp_supervisor", "/vn200", "/arduino", "/microhard_gs", "/hil_sim",
         "/hil_sim_io", "/flight_markers", "/recorder"]
# Topic: the node that must publish it.
TOPICS = {"/clock": "/hil_sim_io", "/hil/lockstep": "/hil_sim_io", "/hil/truth": "/hil_sim", "/ins": "/vn200", "/attitude": "/vn200",
          "/gps_position": "/vn200", "/gps_velocity": "/vn200", "/imu_PQR_acceleration": "/vn200",
          "/servo_op": "/controller_DG808", "/data": "/controller_DG808", "/to_hil": "/controller_DG808",
          "/pwm": "/arduino", "/decision_status": "/arduino", "/home": "/arduino", "/way": "/microhard_gs",
          "/flight_markers": "/flight_markers", "/odom": "/vn200", "/tf": "/vn200", "/tf_static": "/vn200"}
FLOWING = ["/clock", "/ins", "/odom", "/servo_op", "/decision_status", "/home", "/way", "/flight_markers"]


@pytest.fixture(scope="module")
def stack():
    with private_master("launch_", "/launch_test") as (master, env, run_dir, start):
        logs = os.path.join(run_dir, "logs")
        # A long flight: the checks run while it flies, and the fixture stops it.
        start(["roslaunch", "--wait", "drone_ros", "DG808_hil.launch", "run_dir:=" + run_dir,
               "out_dir:=" + os.path.join(run_dir, "out"), "duration_s:=3600", "crash_at_s:=-1", "fault:=none",
               "gs_udp_bind_port:=%d" % free_port(socket.SOCK_DGRAM),
               "gs_udp_remote_port:=%d" % free_port(socket.SOCK_DGRAM)])
        start(["roslaunch", "--wait", "drone_ros", "view.launch", "rviz:=false"])
        start(["roslaunch", "--wait", "drone_ros", "record.launch", "aircraft:=DG808", "mode:=hil",
               "out_dir:=" + logs])
        yield master, env, logs


def test_every_node_of_the_launch_files_comes_up(stack):
    master, _, _ = stack

    def missing():
        up = {n for kind in master.getSystemState() for _, ns in kind for n in ns}
        return [n for n in NODES if n not in up]
    assert wait_for(lambda: not missing()), "not up: %s" % missing()


def test_every_interface_topic_has_its_publisher(stack):
    master, _, _ = stack

    def absent():
        pubs = dict(master.getSystemState()[0])
        return ["%s (from %s)" % (t, n) for t, n in TOPICS.items() if n not in pubs.get(t, [])]
    assert wait_for(lambda: not absent()), "no publisher: %s" % absent()


def test_one_tf_tree_has_one_owner_the_ins_node(stack):
    """REP-105: map -> odom -> base_link -> vn200 all come from the vn200 node; a second
    broadcaster (flight_markers used to put map -> base_link on /tf) would make a second tree."""
    master, _, _ = stack

    def tf_publishers():
        pubs = dict(master.getSystemState()[0])
        return sorted(pubs.get("/tf", [])), sorted(pubs.get("/tf_static", []))
    assert wait_for(lambda: tf_publishers()[0]), "no /tf publisher"
    assert tf_publishers() == (["/vn200"], ["/vn200"])


@pytest.fixture(scope="module")
def echoes(stack):
    """One `rostopic echo -n 1` per flowing topic, all started at once: each waits for its topic
    beside the others instead of after them. Each test reads its own; any still running at the
    end is stopped."""
    _, env, _ = stack
    procs = {}
    try:
        for topic in FLOWING:
            procs[topic] = subprocess.Popen(["rostopic", "echo", "-n", "1", "--noarr", topic], env=env,
                                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                            start_new_session=True)
        yield procs
    finally:
        stop(list(procs.values()))
        for p in procs.values():
            p.stdout.close()
            p.stderr.close()


@pytest.mark.parametrize("topic", FLOWING)
def test_the_topic_carries_messages(echoes, topic):
    p = echoes[topic]
    out, err = p.communicate(timeout=180)
    assert p.returncode == 0 and out.strip(), "%s: nothing within the time: %s" % (topic, err[-500:])


def test_the_recorder_writes_a_dated_log_of_aircraft_and_mode(stack):
    _, _, logs = stack
    found = wait_for(lambda: glob.glob(os.path.join(logs, "*-DG808-hil.bag*")), 60.0)
    assert found, os.listdir(logs) if os.path.isdir(logs) else "no log folder"


# Every node of the HiL stack that reports on /diagnostics, the simulator included.
REPORTERS = ["vn200", "controller_DG808", "arduino", "microhard_gs", "hp_supervisor", "hil_sim"]


def test_every_diagnostic_falls_under_exactly_one_aggregator_analyzer(stack):
    """A lab's monitor groups /diagnostics with launch/diagnostics_aggregator.yaml's analyzers
    (diagnostic_aggregator's GenericAnalyzer matches a status whose name contains one of its
    strings): a status under none is lost in "Other", one under two is shown twice."""
    _, env, _ = stack
    path = os.path.join(os.path.dirname(__file__), "..", "diagnostics_aggregator.yaml")
    with open(path) as f:
        analyzers = yaml.safe_load(f)["analyzers"]
    names, deadline = set(), time.time() + 180
    while time.time() < deadline:
        names |= {st["name"] for m in echo(env, "/diagnostics", 30) for st in m["status"]}
        if all(any(n.startswith(r + ":") for n in names) for r in REPORTERS):
            break
    assert all(any(n.startswith(r + ":") for n in names) for r in REPORTERS), sorted(names)
    for n in sorted(names):
        under = [k for k, a in analyzers.items() if any(c in n for c in a.get("contains", []))]
        assert len(under) == 1, "%r falls under %s" % (n, under or "no analyzer")
