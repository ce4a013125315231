"""MAVProxy, a real ground station, flies microhard_gs over UDP on loopback: it loads a waypoint
file as its users write them (`QGC WPL 110`, home in row 0, waypoints in frame 3), lists the
mission back, has a mission above the ceiling refused, names who flies, and sees no fence breach."""
import os

import pytest

from stack_testing import gs_harness as gh  # noqa: E402
from stack_testing.gs_harness import mavlink  # noqa: E402
from stack_testing.mavproxy_gcs import MavProxy, read_qgc_wpl, write_qgc_wpl  # noqa: E402

from gs_way_plan import assert_plan_flies

NAV_WAYPOINT = mavlink.MAV_CMD_NAV_WAYPOINT
GOOD = [(300.0, 0.0, 200.0), (600.0, 250.0, 250.0), (300.0, 500.0, 300.0)]  # north, east, height ft


@pytest.fixture(scope="module")
def gcs():
    system = gh.GsSystem(udp_client=False)
    mavproxy = None
    try:
        mavproxy = MavProxy(system.gcs_port)
        assert mavproxy.wait_for("online system 1", 60) is not None, mavproxy.output()
        yield system, mavproxy
    finally:
        if mavproxy is not None:
            mavproxy.stop()
        system.stop()


def wpl_rows(legs):
    """Row 0 is home (frame 0, MSL), as MAVProxy writes it; then the legs in frame 3."""
    rows = [(1, mavlink.MAV_FRAME_GLOBAL, NAV_WAYPOINT, gh.HOME[0], gh.HOME[1], gh.HOME[2])]
    for north, east, height in legs:
        lat, lon = gh.local_to_latlon(north, east)
        rows.append((0, mavlink.MAV_FRAME_GLOBAL_RELATIVE_ALT, NAV_WAYPOINT, lat, lon, height / gh.FT_PER_M))
    return rows


def load(gcs, name, legs):
    system, mavproxy = gcs
    path = os.path.join(mavproxy.home, name)
    write_qgc_wpl(path, wpl_rows(legs))
    system.drain_events()
    mark = mavproxy.mark()
    mavproxy.command("wp load " + path)
    ack = mavproxy.wait_for("Got MISSION_ACK", 30, since=mark)
    return ack, mark


def listed(gcs):
    """`wp list`: MAVProxy downloads the mission and saves it as a waypoint file; its rows."""
    _, mavproxy = gcs
    mark = mavproxy.mark()
    mavproxy.command("wp list")
    # Not just "Saved": MAVProxy fetches the vehicle's parameters meanwhile and prints "Saved 24
    # parameters to ..." when it has them, which in CI came first (2026-12-07).
    saved = mavproxy.wait_for(" waypoints to ", 30, since=mark)
    assert saved is not None, mavproxy.output(mark)
    return read_qgc_wpl(saved.split(" to ", 1)[1].strip())


def hold_good_mission(gcs):
    ack, _ = load(gcs, "good.txt", GOOD)
    assert ack is not None and "ACCEPTED" in ack
    assert gcs[0].wait_event(lambda e: e["topic"] == "way", 10) is not None
    gcs[0].drain_events()


def test_wp_load_of_a_frame_3_file_flies_its_waypoints_and_not_its_home_row(gcs):
    system, mavproxy = gcs
    ack, mark = load(gcs, "good.txt", GOOD)
    assert ack is not None and "ACCEPTED" in ack, mavproxy.output(mark)
    assert_plan_flies(system.wait_event(lambda e: e["topic"] == "way", 10), GOOD, 0.5, 0.01)


def test_wp_list_gives_the_file_back_in_its_frames(gcs):
    hold_good_mission(gcs)
    rows = listed(gcs)
    expected = wpl_rows(GOOD)
    assert [(r[0], r[1]) for r in rows] == [(e[1], e[2]) for e in expected]
    for got, want in zip(rows, expected):
        assert got[2] == pytest.approx(want[3], abs=6e-7)  # MAVProxy saves 6 decimals
        assert got[3] == pytest.approx(want[4], abs=6e-7)
        assert got[4] == pytest.approx(want[5], abs=1e-3)


def test_file_with_a_waypoint_above_the_ceiling_is_refused_and_the_old_mission_kept(gcs):
    system, mavproxy = gcs
    hold_good_mission(gcs)
    ack, mark = load(gcs, "too_high.txt", [(300.0, 0.0, 200.0), (600.0, 0.0, 600.0)])
    assert ack is not None and "INVALID_PARAM7" in ack, mavproxy.output(mark)
    assert mavproxy.wait_for("ceiling", 10, since=mark) is not None
    assert system.wait_event(lambda e: e["topic"] == "way", 1.0) is None
    assert len(listed(gcs)) == len(wpl_rows(GOOD))


def test_mavproxy_names_who_flies(gcs):
    system, mavproxy = gcs
    mark = mavproxy.mark()
    system.send_decision(1, 1)  # the HA takes over: NO_COMMAND
    assert mavproxy.wait_for("Mode HA", 20, since=mark) is not None, mavproxy.output(mark)
    mark = mavproxy.mark()
    system.send_decision(4, 0)  # the pilot's PIC switch
    assert mavproxy.wait_for("Mode MANUAL", 20, since=mark) is not None, mavproxy.output(mark)


def test_no_fence_breach_is_reported_when_there_is_no_fence(gcs):
    _, mavproxy = gcs
    mark = mavproxy.mark()
    mavproxy.command("status SYS_STATUS")  # shows that SYS_STATUS has reached its modules
    assert mavproxy.wait_for("SYS_STATUS", 10, since=mark) is not None
    assert "fence breach" not in mavproxy.output()
