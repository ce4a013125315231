"""Flight logs: launch/record.launch records a flight (played back from a scripted bag) under a
fresh <date>-<aircraft>-<mode>.bag name, and the report tool makes the report from that log."""
import datetime
import os
import signal
import subprocess
import time

import pytest
import rosbag
import rosgraph

HERE = os.path.dirname(os.path.abspath(__file__))

import scripted_flight  # noqa: E402
from report_core import flight_name  # noqa: E402
from test_flight_report import expected_switches, page, run  # noqa: E402
from stack_tools import ports

RECORDED = ("/hil/truth", "/decision_status", "/servo_op", "/pwm", "/ins", "/data", "/way")


def test_two_logs_started_in_the_same_second_get_different_names(tmp_path):
    when = datetime.datetime(2026, 11, 23, 18, 30, 5)
    first = flight_name.reserve(str(tmp_path / "logs"), "DG808", "hil", when)
    second = flight_name.reserve(str(tmp_path / "logs"), "DG808", "hil", when)
    assert os.path.basename(first) == "2026-11-23_183005-DG808-hil.bag"
    assert os.path.basename(second) == "2026-11-23_183005-DG808-hil_1.bag"
    with open(first, "w") as f:
        f.write("an earlier flight")
    third = flight_name.reserve(str(tmp_path / "logs"), "DG808", "hil", when)
    assert third not in (first, second)
    with open(first) as f:
        assert f.read() == "an earlier flight"


def test_a_name_that_would_break_the_log_name_is_refused(tmp_path):
    with pytest.raises(ValueError, match="aircraft"):
        flight_name.reserve(str(tmp_path), "DG-808", "hil", datetime.datetime.now())


def _free_port():
    return ports.free_port()


def _bytes_read_by(argument):
    """rchar of /proc/PID/io summed over the processes whose command line holds argument."""
    total = 0
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            with open("/proc/%s/cmdline" % pid, "rb") as f:
                if argument.encode() not in f.read().split(b"\0"):
                    continue
            with open("/proc/%s/io" % pid) as f:
                total += int(next(line for line in f if line.startswith("rchar:")).split()[1])
        except (OSError, StopIteration, ValueError):
            continue
    return total


def _wait(predicate, timeout_s, what):
    deadline = time.time() + timeout_s
    while time.time() < deadline:
        if predicate():
            return
        time.sleep(0.05)
    raise AssertionError("timed out waiting for " + what)


def test_record_launch_logs_a_flight_the_report_reads(tmp_path):
    source = tmp_path / "played.bag"
    scripted_flight.write(str(source), with_truth=True)
    out_dir = tmp_path / "logs"
    env = dict(os.environ)
    port = _free_port()
    env.update(ROS_MASTER_URI="http://127.0.0.1:%d" % port, ROS_IP="127.0.0.1",
               ROS_LOG_DIR=str(tmp_path / "ros_log"))
    env.pop("ROS_HOSTNAME", None)
    procs = []

    def start(cmd):
        log = open(tmp_path / ("%s.log" % os.path.basename(cmd[0])), "ab")
        p = subprocess.Popen(cmd, env=env, stdout=log, stderr=log, start_new_session=True)
        procs.append(p)
        return p

    try:
        start(["rosmaster", "--core", "-p", str(port)])
        launch = start(["roslaunch", "drone_ros", "record.launch", "aircraft:=DG808", "mode:=hil",
                        "out_dir:=%s" % out_dir])

        master = rosgraph.Master("/test_record_flight", master_uri=env["ROS_MASTER_URI"])

        def recorder_subscribed():
            # What `rostopic info /decision_status` lists, asked of the master in this process.
            try:
                subscribers = dict(master.getSystemState()[1])
            except OSError:  # the master is not up yet
                return False
            return "/recorder" in subscribers.get("/decision_status", [])
        _wait(recorder_subscribed, 60, "the recorder to subscribe")
        # Every message queued, none dropped when a loaded machine lets the recorder fall behind.
        played = subprocess.run(["rosbag", "play", "-q", "-r", "4", "--queue", "100000",
                                 "--wait-for-subscribers", str(source)],
                                env=env, capture_output=True, text=True, timeout=300)
        assert played.returncode == 0, played.stderr
        logs = sorted(os.listdir(out_dir))
        # While it records: the name reserved, and rosbag's .active file it will become.
        assert len(logs) == 2 and logs[1] == logs[0] + ".active", logs
        name = logs[0]

        # The flight is over when the recorder has taken in what it was sent: rosbag play returns
        # once it has published, while on a loaded machine the last messages are still on their
        # way to the recorder; Ctrl-C before it has read them loses them, as Ctrl-C during a
        # flight would. Taken in: the recorder's bytes read (/proc/PID/io) still for a second.
        reads = []

        def recorder_read_everything():
            reads.append(_bytes_read_by("__name:=recorder"))
            return len(reads) > 20 and len(set(reads[-20:])) == 1
        _wait(recorder_read_everything, 60, "the recorder to read what it was sent")

        # As a flight ends: roslaunch stopped with Ctrl-C, the recorder closes the bag.
        os.killpg(launch.pid, signal.SIGINT)
        launch.wait(timeout=60)
        assert sorted(os.listdir(out_dir)) == [name]
        assert name.endswith("-DG808-hil.bag")
        datetime.datetime.strptime(name[:17], "%Y-%m-%d_%H%M%S")

        with rosbag.Bag(str(source)) as bag:
            played_counts = {t: bag.get_message_count(t) for t in RECORDED}
        with rosbag.Bag(str(out_dir / name)) as bag:
            recorded_counts = {t: bag.get_message_count(t) for t in RECORDED}
        assert recorded_counts == played_counts
    finally:
        for p in reversed(procs):
            if p.poll() is None:
                os.killpg(p.pid, signal.SIGINT)
                try:
                    p.wait(timeout=30)
                except subprocess.TimeoutExpired:
                    os.killpg(p.pid, signal.SIGKILL)
                    p.wait()

    result = run(str(out_dir / name), "--out", str(tmp_path / "report"))
    assert result.returncode == 0, result.stderr
    _, rows = page(tmp_path / "report" / "index.html")
    assert [(r[2], r[3], r[4].split(" (")[0]) for r in rows] == [
        (s[1], s[2], "NO_COMMAND" if s[3] else "none") for s in expected_switches()]
    assert float(rows[0][1]) == pytest.approx(expected_switches()[0][0], abs=0.01)
