"""A real MAVLink client (pymavlink) talks to microhard_gs over UDP on loopback: the vehicle,
its parameters, missions (good and bad), operator commands and decision-logic announcements."""
import json
import os
import time

import pytest
import yaml

from stack_testing import gs_harness as gh  # noqa: E402
from stack_testing.gs_harness import mavlink  # noqa: E402

from gs_way_plan import assert_plan_flies

TEN = [(100.0 * i, 80.0 * (i % 3), 150.0 + 10.0 * i) for i in range(10)]


@pytest.fixture(scope="module")
def gs():
    system = gh.GsSystem()
    yield system
    system.stop()


def hold_ten_waypoint_mission(gs):
    """Uploads the 10-waypoint mission and waits until its plan is on /way."""
    gs.drain_events()
    ack = gh.upload_mission(gs.conn, ten_waypoint_mission())
    assert ack is not None and ack.type == mavlink.MAV_MISSION_ACCEPTED
    assert gs.wait_event(lambda e: e["topic"] == "way", 5) is not None
    gs.drain_events()


def ten_waypoint_mission():
    return [gh.waypoint(i, n, e, h) for i, (n, e, h) in enumerate(TEN)]


def test_ground_station_sees_a_fixed_wing_vehicle_with_telemetry(gs):
    hb = gs.conn.wait_heartbeat(timeout=5)
    assert hb.type == mavlink.MAV_TYPE_FIXED_WING
    assert hb.autopilot == mavlink.MAV_AUTOPILOT_GENERIC
    assert (hb.get_srcSystem(), hb.get_srcComponent()) == (1, 1)
    seen = {}
    deadline = time.time() + 5
    wanted = {"SYS_STATUS", "ATTITUDE", "GLOBAL_POSITION_INT", "VFR_HUD", "GPS_RAW_INT", "HOME_POSITION"}
    while time.time() < deadline and not wanted <= set(seen):
        m = gs.conn.recv_match(blocking=True, timeout=0.5)
        if m is not None:
            seen[m.get_type()] = m
    assert wanted <= set(seen), "missing %s" % (wanted - set(seen))
    pos = seen["GLOBAL_POSITION_INT"]
    assert pos.lat == pytest.approx(gh.HOME[0] * 1e7, abs=2)
    assert pos.lon == pytest.approx(gh.HOME[1] * 1e7, abs=2)
    assert seen["VFR_HUD"].airspeed == pytest.approx(55.0 / gh.FT_PER_M, rel=1e-3)
    assert seen["GPS_RAW_INT"].fix_type == mavlink.GPS_FIX_TYPE_3D_FIX
    assert seen["HOME_POSITION"].latitude == pytest.approx(gh.HOME[0] * 1e7, abs=2)


def test_autopilot_version_advertises_mission_int_and_mavlink2(gs):
    gh.command_long(gs.conn, mavlink.MAV_CMD_REQUEST_MESSAGE, mavlink.MAVLINK_MSG_ID_AUTOPILOT_VERSION)
    ack = gh.wait_command_ack(gs.conn, mavlink.MAV_CMD_REQUEST_MESSAGE)
    assert ack is not None and ack.result == mavlink.MAV_RESULT_ACCEPTED
    version = gs.conn.recv_match(type="AUTOPILOT_VERSION", blocking=True, timeout=5)
    assert version is not None
    assert version.capabilities & mavlink.MAV_PROTOCOL_CAPABILITY_MISSION_INT
    assert version.capabilities & mavlink.MAV_PROTOCOL_CAPABILITY_MAVLINK2


def download_parameters(conn, timeout_s=10.0):
    conn.mav.param_request_list_send(1, 1)
    got = {}
    count = None
    deadline = time.time() + timeout_s
    while time.time() < deadline and (count is None or len(got) < count):
        m = conn.recv_match(type="PARAM_VALUE", blocking=True, timeout=0.5)
        if m is None:
            if count is not None:  # ask for what is missing, as QGroundControl does
                for index in set(range(count)) - set(got):
                    conn.mav.param_request_read_send(1, 1, b"", index)
            continue
        count = m.param_count
        got[m.param_index] = m
    return count, got


def aircraft_tunables():
    """The aircraft's tunables (tunables.yaml, the one list the controller takes too) by MAVLink
    id, with their values in controller_param.yaml."""
    with open(os.path.join(gh.AIRCRAFT_DIR, "controller_param.yaml")) as f:
        values = yaml.safe_load(f)
    with open(os.path.join(gh.AIRCRAFT_DIR, "tunables.yaml")) as f:
        tunables = yaml.safe_load(f)["tunables"]
    return {t.get("mav_id", t["name"]): values[t["name"]] for t in tunables}


def test_parameter_download_completes_with_the_aircrafts_controller_tunables(gs):
    expected = aircraft_tunables()
    count, got = download_parameters(gs.conn)
    assert count == len(expected)
    assert sorted(got) == list(range(count))
    by_id = {m.param_id: gh.param_value(m) for m in got.values()}
    assert set(by_id) == set(expected)
    for param_id, value in expected.items():
        assert by_id[param_id] == pytest.approx(value, rel=1e-6), param_id
    assert gs.diagnostic("parameters_served") == str(count)


def test_parameter_read_by_name_gives_the_value_in_the_aircraft_file(gs):
    gs.conn.mav.param_request_read_send(1, 1, b"KpLon", -1)
    m = gh.wait_param_value(gs.conn, "KpLon")
    assert m is not None and m.param_value == pytest.approx(aircraft_tunables()["KpLon"])


def test_parameter_set_without_a_controller_is_refused_and_says_so(gs):
    before = aircraft_tunables()["KpLon"]
    gs.conn.mav.param_set_send(1, 1, b"KpLon", 0.005, mavlink.MAV_PARAM_TYPE_REAL32)
    echo = gh.wait_param_value(gs.conn, "KpLon")
    assert echo is not None and echo.param_value == pytest.approx(before)
    assert gh.wait_statustext(gs.conn, "controller not running") is not None
    assert float(gs.rosparam("/controller_DG808/KpLon")) == pytest.approx(before)


def assert_plan_is_ten(event, tolerance_ft=0.5):
    assert_plan_flies(event, TEN, tolerance_ft, 0.01)
    assert event["velocity"][:10] == pytest.approx([60.0] * 10)


def test_ten_waypoint_mission_is_accepted_and_appears_on_way(gs):
    gs.drain_events()
    ack = gh.upload_mission(gs.conn, ten_waypoint_mission())
    assert ack is not None and ack.type == mavlink.MAV_MISSION_ACCEPTED
    assert_plan_is_ten(gs.wait_event(lambda e: e["topic"] == "way", 5))
    items = gh.download_mission(gs.conn)
    assert [(i.seq, i.x, i.y) for i in items] == [(m.seq, m.x, m.y) for m in ten_waypoint_mission()]
    current = gs.conn.recv_match(type="MISSION_CURRENT", blocking=True, timeout=5)
    assert current is not None and current.seq == 0


@pytest.mark.parametrize("legs,refusal,said", [
    ([(0, 0, 200), (300, 0, 600), (600, 0, 200)], mavlink.MAV_MISSION_INVALID_PARAM7, "ceiling"),
    ([(10.0 * i, 0, 200) for i in range(33)], mavlink.MAV_MISSION_NO_SPACE, "33 items"),
], ids=["waypoint_at_600_ft", "33_items"])
def test_a_refused_mission_is_said_and_the_old_mission_kept(gs, legs, refusal, said):
    hold_ten_waypoint_mission(gs)
    ack = gh.upload_mission(gs.conn, [gh.waypoint(i, n, e, h) for i, (n, e, h) in enumerate(legs)])
    assert ack is not None and ack.type == refusal
    assert gh.wait_statustext(gs.conn, said) is not None
    assert len(gh.download_mission(gs.conn)) == 10
    assert gs.wait_event(lambda e: e["topic"] == "way", 1.0) is None


def test_legacy_mission_item_upload_is_accepted(gs):
    gs.drain_events()
    ack = gh.upload_mission(gs.conn, ten_waypoint_mission(), legacy=True)
    assert ack is not None and ack.type == mavlink.MAV_MISSION_ACCEPTED
    # float32 degrees resolve about 2 ft at this longitude: why MISSION_ITEM_INT exists
    assert_plan_is_ten(gs.wait_event(lambda e: e["topic"] == "way", 5), tolerance_ft=3.0)


FRAMES = [mavlink.MAV_FRAME_GLOBAL, mavlink.MAV_FRAME_GLOBAL_RELATIVE_ALT, mavlink.MAV_FRAME_GLOBAL_INT,
          mavlink.MAV_FRAME_GLOBAL_RELATIVE_ALT_INT]
FLOAT_TWIN = {mavlink.MAV_FRAME_GLOBAL_INT: mavlink.MAV_FRAME_GLOBAL,
              mavlink.MAV_FRAME_GLOBAL_RELATIVE_ALT_INT: mavlink.MAV_FRAME_GLOBAL_RELATIVE_ALT}


@pytest.mark.parametrize("legacy", [False, True], ids=["MISSION_ITEM_INT", "MISSION_ITEM"])
@pytest.mark.parametrize("frame", FRAMES, ids=["frame0", "frame3", "frame5", "frame6"])
def test_mission_in_every_global_frame_flies_the_same_heights_and_downloads_in_its_frame(gs, frame, legacy):
    """0 and 5 are MSL (home's altitude + the height), 3 and 6 heights above home: /way gets the
    same plan, and a download answers in the frame uploaded (a MISSION_ITEM gives 5/6 as 0/3)."""
    legs = [(200.0, 0.0, 150.0), (400.0, 150.0, 250.0), (600.0, -100.0, 350.0)]
    items = [gh.waypoint(i, n, e, h, frame) for i, (n, e, h) in enumerate(legs)]
    gs.drain_events()
    ack = gh.upload_mission(gs.conn, items, legacy=legacy)
    assert ack is not None and ack.type == mavlink.MAV_MISSION_ACCEPTED
    assert_plan_flies(gs.wait_event(lambda e: e["topic"] == "way", 5), legs, 3.0, 0.05)
    as_int = gh.download_mission(gs.conn)
    assert [m.frame for m in as_int] == [frame] * 3
    assert [m.z for m in as_int] == pytest.approx([m.z for m in items])
    as_float = gh.download_mission(gs.conn, legacy=True)
    assert [m.frame for m in as_float] == [FLOAT_TWIN.get(frame, frame)] * 3
    assert [m.x for m in as_float] == pytest.approx([m.x * 1e-7 for m in items], abs=1e-5)


def test_ground_station_learns_the_mode_names_and_they_match_the_shipped_pymavlink_map(gs):
    """AVAILABLE_MODES (what QGroundControl reads) and gcs/pymavlink_custom_mode_map.json (what
    MAVProxy reads through pymavlink) name the same custom modes the same way."""
    gh.command_long(gs.conn, mavlink.MAV_CMD_REQUEST_MESSAGE, mavlink.MAVLINK_MSG_ID_AVAILABLE_MODES, 0)
    ack = gh.wait_command_ack(gs.conn, mavlink.MAV_CMD_REQUEST_MESSAGE)
    assert ack is not None and ack.result == mavlink.MAV_RESULT_ACCEPTED
    modes = {}
    deadline = time.time() + 5
    while time.time() < deadline and len(modes) < 5:
        m = gs.conn.recv_match(type="AVAILABLE_MODES", blocking=True, timeout=0.5)
        if m is not None:
            modes[m.custom_mode] = m
    assert {k: m.mode_name for k, m in modes.items()} == {
        0: "HP", 1: "HA", 2: "RECOVERING", 3: "HA_LATCHED", 4: "MANUAL"}
    selectable = {m.mode_name for m in modes.values()
                  if not m.properties & mavlink.MAV_MODE_PROPERTY_NOT_USER_SELECTABLE}
    assert selectable == {"HP", "HA"}
    with open(os.path.join(gh.HERE, "..", "gcs", "pymavlink_custom_mode_map.json")) as f:
        shipped = json.load(f)[str(mavlink.MAV_TYPE_FIXED_WING)]
    assert {int(k): v for k, v in shipped.items() if int(k) in modes} == {k: m.mode_name for k, m in modes.items()}


def test_clearing_the_mission_publishes_an_empty_plan(gs):
    hold_ten_waypoint_mission(gs)
    gs.conn.mav.mission_clear_all_send(1, 1, mavlink.MAV_MISSION_TYPE_MISSION)
    ack = gs.conn.recv_match(type="MISSION_ACK", blocking=True, timeout=5)
    assert ack.type == mavlink.MAV_MISSION_ACCEPTED
    event = gs.wait_event(lambda e: e["topic"] == "way", 5)
    assert event is not None and event["fp"] == 0
    assert gh.download_mission(gs.conn) == []


@pytest.mark.parametrize("command,params,expected", [
    (mavlink.MAV_CMD_DO_SET_MODE, (mavlink.MAV_MODE_FLAG_CUSTOM_MODE_ENABLED, 1), 2),  # SELECT_HA
    (mavlink.MAV_CMD_DO_SET_MODE, (mavlink.MAV_MODE_FLAG_CUSTOM_MODE_ENABLED, 0), 1),  # SELECT_HP
    (mavlink.MAV_CMD_PREFLIGHT_REBOOT_SHUTDOWN, (0, 1), 3),                           # RESTART_HP
    (mavlink.MAV_CMD_ACTUATOR_TEST, (), 4),                                            # SELF_TEST
])
def test_operator_command_is_acknowledged_and_forwarded_to_the_ha(gs, command, params, expected):
    gs.drain_events()
    gh.command_long(gs.conn, command, *params)
    ack = gh.wait_command_ack(gs.conn, command)
    assert ack is not None and ack.result == mavlink.MAV_RESULT_ACCEPTED
    event = gs.wait_event(lambda e: e["topic"] == "operator_command", 5)
    assert event is not None and event["command"] == expected


def test_operator_requests_go_out_sealed_with_the_crc_the_ha_checks_each_with_its_own_id(gs):
    # The HA drops a request whose CRC-32 does not match (rosserial's 8-bit sum misses a +1/-1
    # byte pair) and ignores a repeat of the request it executed last: each request goes out
    # sealed, with an id of its own.
    gs.drain_events()
    ids = []
    for _ in range(2):
        gh.command_long(gs.conn, mavlink.MAV_CMD_DO_SET_MODE, mavlink.MAV_MODE_FLAG_CUSTOM_MODE_ENABLED, 1)
        ack = gh.wait_command_ack(gs.conn, mavlink.MAV_CMD_DO_SET_MODE)
        assert ack is not None and ack.result == mavlink.MAV_RESULT_ACCEPTED
        event = gs.wait_event(lambda e: e["topic"] == "operator_command", 5)
        assert event is not None and event["command"] == 2 and event["crc_ok"]
        ids.append(event["request_id"])
    assert ids[1] == (ids[0] + 1) & 0xFFFFFFFF


def test_rebooting_the_ha_from_the_ground_is_denied(gs):
    gs.drain_events()
    gh.command_long(gs.conn, mavlink.MAV_CMD_PREFLIGHT_REBOOT_SHUTDOWN, 1, 0)
    ack = gh.wait_command_ack(gs.conn, mavlink.MAV_CMD_PREFLIGHT_REBOOT_SHUTDOWN)
    assert ack is not None and ack.result == mavlink.MAV_RESULT_DENIED
    assert gs.wait_event(lambda e: e["topic"] == "operator_command", 1.0) is None


def test_decision_switch_to_ha_reaches_the_operator_naming_the_reasons(gs):
    gs.send_decision(0, 0)
    assert gs.decision_reached_node(0, 0.0)
    gs.send_decision(1, 1 | 64)  # NO_COMMAND and STALL
    st = gh.wait_statustext(gs.conn, "HP->HA")
    assert st is not None
    assert "NO_COMMAND" in st.text and "STALL" in st.text
    assert st.severity == mavlink.MAV_SEVERITY_WARNING
    hb = gs.conn.recv_match(type="HEARTBEAT", blocking=True, timeout=3)
    assert hb.custom_mode == 1


def test_self_test_in_the_air_is_refused(gs):
    gs.send_decision(0, 0, altitude_agl_ft=150.0)
    assert gs.decision_reached_node(0, 150.0)
    gs.drain_events()
    gh.command_long(gs.conn, mavlink.MAV_CMD_ACTUATOR_TEST)
    ack = gh.wait_command_ack(gs.conn, mavlink.MAV_CMD_ACTUATOR_TEST)
    assert ack is not None and ack.result == mavlink.MAV_RESULT_TEMPORARILY_REJECTED
    assert gs.wait_event(lambda e: e["topic"] == "operator_command", 1.0) is None
    gs.send_decision(0, 0, altitude_agl_ft=0.0)
    assert gs.decision_reached_node(0, 0.0)  # back on the ground for whatever runs next


def test_corrupt_frames_are_counted_and_dropped_and_the_link_keeps_working(gs):
    before = int(gs.diagnostic("frames_bad_crc"))
    frame = bytearray(gs.conn.mav.param_request_list_encode(1, 1).pack(gs.conn.mav))
    frame[-1] ^= 0xFF  # break the CRC
    for _ in range(5):
        gs.conn.write(bytes(frame))
    # Counted once the node has read them: the diagnostics are waited for, not a fixed time.
    assert int(gs.wait_diagnostic("frames_bad_crc", lambda v: int(v) >= before + 5)) >= before + 5
    count, got = download_parameters(gs.conn)
    assert count == len(aircraft_tunables()) and len(got) == count
