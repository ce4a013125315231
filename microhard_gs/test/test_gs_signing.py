"""With a MAVLink 2 signing key configured, only correctly signed messages change anything:
unsigned and badly signed ones are refused and counted, while read-only requests still work."""
import contextlib

import pytest

from stack_testing import gs_harness as gh  # noqa: E402
from stack_testing.gs_harness import mavlink  # noqa: E402

KEY = bytes(range(1, 33))
WRONG_KEY = bytes(range(101, 133))
SELECT_HA = (mavlink.MAV_MODE_FLAG_CUSTOM_MODE_ENABLED, 1)


@pytest.fixture(scope="module")
def signed_gs(tmp_path_factory):
    key_file = tmp_path_factory.mktemp("signing") / "gs.key"
    key_file.write_text(KEY.hex() + "\n")
    # pymavlink checks every signature in Python: a low telemetry rate keeps its backlog short.
    system = gh.GsSystem(launch_args={"signing_key_file": str(key_file), "telemetry_rate_hz": 2.0})
    system.conn.setup_signing(KEY, sign_outgoing=True)
    yield system
    system.stop()


@contextlib.contextmanager
def client_signing(gs, key=KEY, sign_outgoing=True):
    """The client sends the block's messages signed with key (or unsigned), then signs with KEY
    again whatever the block raised: the module's other tests share the client."""
    signing = gs.conn.mav.signing
    signing.secret_key, signing.sign_outgoing = key, sign_outgoing
    try:
        yield
    finally:
        signing.secret_key, signing.sign_outgoing = KEY, True


def test_signed_command_is_accepted_and_forwarded(signed_gs):
    gs = signed_gs
    gs.drain_events()
    gh.command_long(gs.conn, mavlink.MAV_CMD_DO_SET_MODE, *SELECT_HA)
    ack = gh.wait_command_ack(gs.conn, mavlink.MAV_CMD_DO_SET_MODE)
    assert ack is not None and ack.result == mavlink.MAV_RESULT_ACCEPTED
    event = gs.wait_event(lambda e: e["topic"] == "operator_command", 5)
    assert event is not None and event["command"] == 2


def test_unsigned_command_is_refused_and_counted(signed_gs):
    gs = signed_gs
    before = int(gs.diagnostic("refused_unsigned"))
    gs.drain_events()
    with client_signing(gs, sign_outgoing=False):
        gh.command_long(gs.conn, mavlink.MAV_CMD_DO_SET_MODE, *SELECT_HA)
        ack = gh.wait_command_ack(gs.conn, mavlink.MAV_CMD_DO_SET_MODE)
    assert ack is not None and ack.result == mavlink.MAV_RESULT_DENIED
    assert gs.wait_event(lambda e: e["topic"] == "operator_command", 1.5) is None
    assert int(gs.diagnostic("refused_unsigned")) >= before + 1


def test_badly_signed_mission_is_refused_and_counted(signed_gs):
    gs = signed_gs
    before = int(gs.diagnostic("refused_bad_signature"))
    gs.drain_events()
    with client_signing(gs, key=WRONG_KEY):
        gs.conn.mav.mission_count_send(1, 1, 3, mavlink.MAV_MISSION_TYPE_MISSION)
        request = gs.conn.recv_match(type=["MISSION_REQUEST_INT", "MISSION_REQUEST"], blocking=True, timeout=1.5)
    assert request is None  # the upload never started
    assert int(gs.diagnostic("refused_bad_signature")) >= before + 1


def test_unsigned_read_only_requests_still_work(signed_gs):
    gs = signed_gs
    with client_signing(gs, sign_outgoing=False):
        gs.conn.mav.param_request_read_send(1, 1, b"mpf_radius", -1)
        value = gs.conn.recv_match(type="PARAM_VALUE", blocking=True, timeout=5)
    assert value is not None and value.param_value == pytest.approx(250.0)


def test_signed_mission_upload_is_accepted(signed_gs):
    gs = signed_gs
    gs.drain_events()
    items = [gh.waypoint(i, 100.0 * i, 0.0, 200.0) for i in range(4)]
    ack = gh.upload_mission(gs.conn, items)
    assert ack is not None and ack.type == mavlink.MAV_MISSION_ACCEPTED
    event = gs.wait_event(lambda e: e["topic"] == "way", 5)
    assert event is not None and event["fp"] == 4
