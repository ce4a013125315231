"""The node's MAVLink telemetry log (~tlog_path) with a real client (pymavlink) on UDP loopback:
what the client sent and what the vehicle answered are in the log, as pymavlink reads a tlog; a
log that cannot be written is said once on the ROS log and in the diagnostics, and the link goes
on. (A whole HiL flight's tlog: drone_ros/report/test/test_report_of_a_hil_fault_flight.py.)"""
import glob
import os
import re
import time

import pytest

from stack_testing import gs_harness as gh  # noqa: E402
from stack_testing.gs_harness import mavlink  # noqa: E402
from stack_testing.tlog_file import tlog_messages


@pytest.fixture(scope="module")
def bench():
    """The master, the parameters, the probe and the client; each test starts its own node."""
    system = gh.GsSystem(node=False)
    try:
        yield system
    finally:
        system.stop()


@pytest.fixture
def node(bench):
    def start(tlog_path):
        bench.start_node({"tlog_path": tlog_path})
        assert bench.conn.wait_heartbeat(timeout=30) is not None
        return bench
    yield start
    if bench.launch is not None:
        bench.stop_node()


def autopilot_version_asked_and_answered(gs):
    gh.command_long(gs.conn, mavlink.MAV_CMD_REQUEST_MESSAGE, mavlink.MAVLINK_MSG_ID_AUTOPILOT_VERSION)
    ack = gh.wait_command_ack(gs.conn, mavlink.MAV_CMD_REQUEST_MESSAGE)
    return ack is not None and ack.result == mavlink.MAV_RESULT_ACCEPTED


def test_the_tlog_holds_the_clients_request_and_the_vehicles_answer(node, tmp_path):
    before_s = time.time()
    gs = node(str(tmp_path / "logs" / "%Y-%m-%d_%H%M%S-DG808-bench.tlog"))
    assert autopilot_version_asked_and_answered(gs)
    # The strftime fields filled in with the start time, the folder made.
    (path,) = glob.glob(str(tmp_path / "logs" / "*.tlog"))
    assert re.fullmatch(r"\d{4}-\d{2}-\d{2}_\d{6}-DG808-bench\.tlog", os.path.basename(path)), path
    deadline = time.time() + 10.0  # written every 0.5 s
    while True:
        messages = tlog_messages(path)
        asked = [m for m in messages if m.get_type() == "COMMAND_LONG" and
                 m.command == mavlink.MAV_CMD_REQUEST_MESSAGE]
        answered = [m for m in messages if m.get_type() == "AUTOPILOT_VERSION"]
        if (asked and answered) or time.time() > deadline:
            break
        time.sleep(0.2)
    assert asked and answered, sorted({m.get_type() for m in messages})
    assert (asked[0].get_srcSystem(), asked[0]._link) == (255, 0)  # received from the client
    assert (answered[0].get_srcSystem(), answered[0]._link) == (1, 3)  # sent by the vehicle
    assert any(m.get_type() == "HEARTBEAT" and m._link == 3 for m in messages)
    assert not [m for m in messages if m.get_type() == "BAD_DATA"]
    assert before_s - 1.0 <= messages[0]._timestamp <= asked[0]._timestamp <= time.time()


def test_a_tlog_that_cannot_be_written_is_said_once_and_the_link_goes_on(node):
    gs = node("/dev/full")  # every write: no space left on device
    error = gs.wait_diagnostic("tlog_error", lambda v: v != "", timeout=10.0)
    assert error == "/dev/full: write failed: No space left on device", error
    time.sleep(1.5)  # three more flush periods: nothing more is said
    assert autopilot_version_asked_and_answered(gs)  # the link goes on
    lost = gs.wait_diagnostic("tlog_records_lost", lambda v: int(v) > 0)
    assert int(lost) > 0 and gs.diagnostic("tlog_records") == "0"
    with open(os.path.join(gs.env["ROS_LOG_DIR"], "roslaunch-%d.log" % gs.master_port), errors="replace") as f:
        said = [line for line in f if "tlog stopped" in line]
    assert len(said) == 1, said
    assert "No space left on device; the ground link goes on without it" in said[0]
