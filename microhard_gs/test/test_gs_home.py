"""Home seen from a real MAVLink client (pymavlink) over UDP loopback: HOME_POSITION is the
home the HA publishes on /home (the probe plays the `arduino` node), GET_HOME_POSITION and
REQUEST_MESSAGE answer it, and MAV_CMD_DO_SET_HOME reaches the HA on the ground and is refused in
flight with the reason."""
import time

import pytest

from stack_testing import gs_harness as gh  # noqa: E402
from stack_testing.gs_harness import mavlink  # noqa: E402


@pytest.fixture(scope="module")
def gs():
    system = gh.GsSystem()
    # The node learns home from the latched /home a moment after it connects, and says so with an
    # unasked HOME_POSITION; a request before that is rightly TEMPORARILY_REJECTED (a ground
    # station retries it). The stories below start from a node that knows home.
    if system.conn.recv_match(type="HOME_POSITION", blocking=True, timeout=30) is None:
        system.stop()
        raise RuntimeError("microhard_gs never sent the home the probe published on /home")
    yield system
    system.stop()


def collect_answer(conn, command, timeout_s=5.0):
    """The COMMAND_ACK for command and every STATUSTEXT and HOME_POSITION seen until it."""
    texts, homes = [], []
    deadline = time.time() + timeout_s
    while time.time() < deadline:
        m = conn.recv_match(type=["COMMAND_ACK", "STATUSTEXT", "HOME_POSITION"], blocking=True, timeout=0.2)
        if m is None:
            continue
        if m.get_type() == "STATUSTEXT":
            texts.append(m.text)
        elif m.get_type() == "HOME_POSITION":
            homes.append(m)
        elif m.command == command:
            return m, texts, homes
    return None, texts, homes


def wait_home_position(conn, timeout_s=5.0):
    return conn.recv_match(type="HOME_POSITION", blocking=True, timeout=timeout_s)


@pytest.mark.parametrize("how", ["GET_HOME_POSITION", "REQUEST_MESSAGE"])
def test_home_position_is_the_home_the_ha_published(gs, how):
    if how == "GET_HOME_POSITION":
        gh.command_long(gs.conn, mavlink.MAV_CMD_GET_HOME_POSITION)
        ack = gh.wait_command_ack(gs.conn, mavlink.MAV_CMD_GET_HOME_POSITION)
    else:
        gh.command_long(gs.conn, mavlink.MAV_CMD_REQUEST_MESSAGE, mavlink.MAVLINK_MSG_ID_HOME_POSITION)
        ack = gh.wait_command_ack(gs.conn, mavlink.MAV_CMD_REQUEST_MESSAGE)
    assert ack is not None and ack.result == mavlink.MAV_RESULT_ACCEPTED
    home = wait_home_position(gs.conn)
    assert home is not None
    assert home.latitude == round(gh.HOME[0] * 1e7)
    assert home.longitude == round(gh.HOME[1] * 1e7)
    assert home.altitude == round(gh.HOME[2] * 1000)


def test_set_home_on_the_ground_reaches_the_ha_with_its_exact_position(gs):
    gs.send_decision(0, 0, altitude_agl_ft=0.0)
    assert gs.decision_reached_node(0, 0.0)
    gs.drain_events()
    lat, lon = 40.1123457, -88.2198765
    gs.conn.mav.command_int_send(1, 1, mavlink.MAV_FRAME_GLOBAL, mavlink.MAV_CMD_DO_SET_HOME, 0, 0,
                                 0, 0, 0, 0, round(lat * 1e7), round(lon * 1e7), 221.5)
    ack = gh.wait_command_ack(gs.conn, mavlink.MAV_CMD_DO_SET_HOME)
    assert ack is not None and ack.result == mavlink.MAV_RESULT_ACCEPTED
    event = gs.wait_event(lambda e: e["topic"] == "operator_command", 5)
    assert event is not None and event["command"] == 5  # OperatorCommand.SET_HOME
    assert event["crc_ok"]  # sealed: the HA acts on no home that changed on the way
    assert not event["use_current"]
    assert event["latitude"] == pytest.approx(lat, abs=1e-9)
    assert event["longitude"] == pytest.approx(lon, abs=1e-9)
    assert event["altitude"] == pytest.approx(221.5)
    # "Here" (param1 = 1): the HA takes its own INS position.
    gs.drain_events()
    gh.command_long(gs.conn, mavlink.MAV_CMD_DO_SET_HOME, 1)
    ack = gh.wait_command_ack(gs.conn, mavlink.MAV_CMD_DO_SET_HOME)
    assert ack is not None and ack.result == mavlink.MAV_RESULT_ACCEPTED
    event = gs.wait_event(lambda e: e["topic"] == "operator_command", 5)
    assert event is not None and event["command"] == 5 and event["use_current"]


def test_set_home_in_flight_is_refused_with_the_reason(gs):
    gs.send_decision(0, 0, altitude_agl_ft=150.0)
    assert gs.decision_reached_node(0, 150.0)
    gs.drain_events()
    gh.command_long(gs.conn, mavlink.MAV_CMD_DO_SET_HOME, 1)
    ack, texts, _ = collect_answer(gs.conn, mavlink.MAV_CMD_DO_SET_HOME)
    assert ack is not None and ack.result == mavlink.MAV_RESULT_TEMPORARILY_REJECTED
    assert "Set home refused: in flight" in texts
    assert gs.wait_event(lambda e: e["topic"] == "operator_command", 1.0) is None
    gs.send_decision(0, 0, altitude_agl_ft=0.0)
    assert gs.decision_reached_node(0, 0.0)  # back on the ground for whatever runs next
