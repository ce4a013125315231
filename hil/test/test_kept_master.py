"""A campaign worker's kept ROS master (hil/campaigns/kept_master.py, hil/ros_master.py,
run_flight.py --master): a flight on it is the flight it is on a master of its own and leaves the
master as it found it; a SIGKILLed node's registrations are forgotten; a master that has died is
started anew; a master that does not answer fails the flight with the reason; none is left
behind, by a campaign or by a worker killed outright."""
import json
import os
import signal
import subprocess
import sys
import uuid
import xmlrpc.client

import pytest

from hil import ros_master
from hil.campaigns import flight as flight_mod
from hil.campaigns import kept_master
from stack_testing import fault_flight
from stack_testing.story_wait import wait_for
from stack_tools.ports import free_port

HERE = os.path.dirname(os.path.abspath(__file__))
RUN_FLIGHT = os.path.join(HERE, "..", "run_flight.py")
# What stack_testing.fault_flight.fly("crash", at_s=15.0) flies.
FLIGHT = ["--seed", "11", "--fault", "crash", "--fault-at", "15", "--fault-duration", "-1", "--duration", "35",
          "--no-bag", "--quiet"]


def alive_holders(token):
    from hil import proc_stat
    return [p for p in flight_mod.holders(token, var=kept_master.CAMPAIGN_VAR) if not proc_stat.dead(p)]


@pytest.fixture
def kept():
    k = kept_master.KeptMaster(uuid.uuid4().hex)
    k.start()
    yield k
    k.stop()
    assert alive_holders(k.token) == []


def rosout_registered(uri):
    return ros_master.registered_nodes(uri) == ["/rosout"]


def parameters(uri):
    return xmlrpc.client.ServerProxy(uri).getParam("/test", "/")[2]


def truth(folder):
    with open(os.path.join(folder, "truth.bin"), "rb") as f:
        return f.read()


def fly(folder, *extra):
    r = flight_mod.run_completed([sys.executable, RUN_FLIGHT] + FLIGHT + ["--folder", str(folder)] + list(extra),
                                 timeout=600)
    assert r.returncode == 0, r.stdout.decode(errors="replace")[-3000:]
    with open(os.path.join(folder, "summary.json")) as f:
        return json.load(f)


def test_a_sigkilled_nodes_topics_and_services_are_forgotten_and_rosout_kept(kept):
    uri = kept.ensure()
    wait_for(lambda: rosout_registered(uri), 60.0, "rosout registered with the kept master")
    master = xmlrpc.client.ServerProxy(uri)
    # What a node SIGKILLed in the last flight leaves: its registrations, at an address now dead.
    dead = "http://127.0.0.1:%d/" % free_port()
    master.registerPublisher("/controller_DG808", "/pwm", "std_msgs/String", dead)
    master.registerSubscriber("/controller_DG808", "/ins_in", "std_msgs/String", dead)
    master.registerService("/controller_DG808", "/controller_DG808/get_loggers", "rosrpc://127.0.0.1:9", dead)
    assert ros_master.registered_nodes(uri) == ["/controller_DG808", "/rosout"]
    assert ros_master.forget_nodes(uri) == ["/controller_DG808"]
    assert rosout_registered(uri)
    assert master.lookupNode("/test", "/controller_DG808")[0] != 1
    assert master.lookupService("/test", "/controller_DG808/get_loggers")[0] != 1


def test_a_flight_on_a_kept_master_is_the_flight_on_its_own_and_leaves_the_master_as_it_found_it(kept, tmp_path):
    uri = kept.ensure()
    wait_for(lambda: rosout_registered(uri), 60.0, "rosout registered with the kept master")
    master = xmlrpc.client.ServerProxy(uri)
    # What a last flight of another aircraft could have left: none of it may reach this one.
    master.setParam("/test", "/controller_DG808/kp_roll", 99.0)
    master.setParam("/test", "/use_sim_time", False)
    # And a flight killed whole past its wall-clock limit never unregistered its nodes.
    master.registerPublisher("/left_by_a_killed_flight", "/left_topic", "std_msgs/String",
                             "http://127.0.0.1:%d/" % free_port())
    run_id = parameters(uri)["run_id"]
    # The crash fault test's flight (hil/faults/test/test_crash.py), on a master of its own and
    # shared with that test, then the same command on the kept master.
    on_own = fault_flight.fly("crash", at_s=15.0)
    on_kept = fly(tmp_path / "kept", "--master", uri)
    assert on_kept["verdict"]["ok"] is True and on_kept["fault"]["took_effect"] is True
    assert truth(tmp_path / "kept") == truth(on_own["_folder"])  # every truth message, byte for byte
    assert on_kept["who_flew"] == on_own["who_flew"]
    # The same master, holding what it held before the flight: roscore's parameters and rosout.
    assert kept.alive() and ros_master.answers(uri)
    assert sorted(parameters(uri)) == ["rosdistro", "rosversion", "run_id"]
    assert parameters(uri)["run_id"] != run_id
    assert rosout_registered(uri)


def test_a_flight_told_of_a_master_that_does_not_answer_dies_saying_so(tmp_path):
    uri = "http://127.0.0.1:%d" % free_port()
    r = flight_mod.run_completed([sys.executable, RUN_FLIGHT] + FLIGHT + ["--folder", str(tmp_path / "f"),
                                                                          "--master", uri], timeout=300)
    assert r.returncode == 1
    with open(tmp_path / "f" / "summary.json") as f:
        s = json.load(f)
    assert s["status"] == "died" and s["error"] == "the ROS master at %s does not answer" % uri


def test_a_master_uri_that_is_not_one_is_refused_on_the_command_line(tmp_path):
    r = subprocess.run([sys.executable, RUN_FLIGHT, "--master", "127.0.0.1:11311", "--folder", str(tmp_path / "f")],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 2
    assert "--master must be a ROS master's URI, http://HOST:PORT" in r.stderr
    assert not os.path.exists(tmp_path / "f" / "summary.json")


def test_a_flight_killed_whole_leaves_registrations_the_next_flight_forgets_before_it_starts(kept):
    uri = kept.ensure()
    wait_for(lambda: rosout_registered(uri), 60.0, "rosout registered with the kept master")
    master = xmlrpc.client.ServerProxy(uri)
    # A flight SIGKILLed whole past its wall-clock limit: run_flight.py never cleaned up after it.
    master.registerPublisher("/controller_DG808", "/pwm", "std_msgs/String", "http://127.0.0.1:%d/" % free_port())
    master.setParam("/test", "/controller_DG808/kp_roll", 99.0)
    ros_master.reset_for_flight(uri)
    # Else the master would send `shutdown` to that address when the next controller registers.
    assert rosout_registered(uri)
    assert sorted(parameters(uri)) == ["rosdistro", "rosversion", "run_id"]


def test_a_kept_master_that_died_is_started_anew_for_the_next_flight(kept):
    uri = kept.ensure()
    pid = xmlrpc.client.ServerProxy(uri).getPid("/test")[2]
    os.killpg(kept.procs[0].pid, signal.SIGKILL)
    kept.procs[0].wait()
    assert not kept.alive()
    again = kept.ensure()
    assert ros_master.answers(again)
    assert xmlrpc.client.ServerProxy(again).getPid("/test")[2] != pid
    assert sorted(parameters(again)) == ["rosdistro", "rosversion", "run_id"]
    wait_for(lambda: rosout_registered(again), 60.0, "the new rosout registered")


def test_a_worker_killed_outright_takes_its_master_and_rosout_with_it():
    token = uuid.uuid4().hex
    worker = subprocess.Popen(
        [sys.executable, "-c", "import sys, time\n"
         "from hil.campaigns.kept_master import KeptMaster\n"
         "k = KeptMaster(sys.argv[1]); k.start(); k.ensure(); print('up', flush=True); time.sleep(600)\n", token],
        stdout=subprocess.PIPE, text=True)
    try:
        assert worker.stdout.readline().strip() == "up"
        assert len(alive_holders(token)) == 2  # rosmaster and rosout
        worker.kill()
        worker.wait()
        wait_for(lambda: alive_holders(token) == [], 30.0, "the master and rosout gone with their worker")
    finally:
        worker.kill()
        worker.wait()
        worker.stdout.close()
        flight_mod.kill_all(token, var=kept_master.CAMPAIGN_VAR)
