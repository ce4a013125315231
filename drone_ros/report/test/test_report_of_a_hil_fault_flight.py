"""flight_report on the bag of a real lockstep HiL flight with a fault (hil/run_flight.py records
it and runs the report, as `make run` does): every figure is drawn and on the page, and the
page's switch list is the flight's switches as the simulator saw them on the servos (summary.json
"who_flew", from the HA's replies in the loop), not as the report read them from the bag. The
same flight's ground-link log (flight.tlog, written by microhard_gs beside the bag) read as
MAVExplorer reads it."""
import os

import pytest

os.environ.setdefault("MAVLINK20", "1")
from pymavlink import mavutil  # noqa: E402  (MAVLINK20 first: the link is MAVLink 2)

from test_flight_report import FIGURES, page, png_size  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
from stack_testing.fault_flight import fly  # noqa: E402  (the fault tests' flights, each flown once per test run)
from stack_testing.tlog_file import tlog_messages  # noqa: E402
from hil import mission  # noqa: E402  (the mission the HiL uploads, as a ground station holds it)
# The page's controller labels (report_core figures.CONTROLLER_LABELS) for the summary's names.
LABELS = {"HP": "HP", "HA": "HA", "RECOVERING": "recovering", "HA_LATCHED": "latched", "MANUAL": "pilot"}


@pytest.fixture(scope="module")
def flight():
    # A NaN aileron for 3 s from 15 s: the HA takes over, the HP is restarted and handed back.
    # hil/faults/test/test_nan.py's flight (with its bag and report), flown once per test run.
    s = fly("nan", at_s=15.0, duration_s=3.0, params=["surface=aileron"], bag=True)
    return s["_folder"], s


def test_every_figure_of_the_fault_flight_is_drawn_and_on_the_page(flight):
    folder, _ = flight
    report = os.path.join(folder, "report")
    text, _ = page(os.path.join(report, "index.html"))
    for name in FIGURES:
        path = os.path.join(report, name)
        assert os.path.exists(path), name
        width, height = png_size(path)
        assert width >= 800 and height >= 450, name
        assert 'src="%s"' % name in text, "%s is not on the page" % name


def test_the_switch_list_is_the_flights_switches_with_their_reasons(flight):
    folder, s = flight
    segs = s["who_flew"]
    assert any(seg["controller"] == "HA" and seg["from_s"] >= 15.0 for seg in segs), segs  # the fault's takeover
    expected = [(b["from_s"], LABELS[a["controller"]], LABELS[b["controller"]], b["why"])
                for a, b in zip(segs, segs[1:])]
    _, rows = page(os.path.join(folder, "report", "index.html"))
    assert len(rows) == len(expected), (rows, expected)
    for row, (t_s, frm, to, why) in zip(rows, expected):
        _, time_cell, from_cell, to_cell, reason_cell, _ = row
        # The bag's /decision_status is stamped by the arduino node within the HA's period.
        assert float(time_cell) == pytest.approx(t_s, abs=0.02), (row, t_s)
        assert (from_cell, to_cell) == (frm, to), (row, frm, to)
        if frm == "HP":  # a takeover: the page names what the HA switched for
            assert why and all(name in reason_cell for name in why), (row, why)
        if to == "HP":   # a hand-back: after the stable window
            assert "HP command valid for" in reason_cell, row


def tlog_records(path):
    """Every message of a tlog as (message, record time [s], link tag: 3 sent by the vehicle, 0
    received)."""
    return [(m, m._timestamp, m._link) for m in tlog_messages(path)]


def test_the_ground_links_tlog_holds_both_directions_on_the_wall_clock(flight):
    folder, s = flight
    path = os.path.join(folder, "flight.tlog")
    assert os.path.isfile(path), "no %s beside the bag" % path  # (pymavlink would try it as a serial port)
    records = tlog_records(path)
    assert len(records) > 100, len(records)
    assert not [m for m, _, _ in records if m.get_type() == "BAD_DATA"]  # every record whole
    sent = [(m, t) for m, t, link in records if link == 3]
    received = [(m, t) for m, t, link in records if link == 0]
    assert len(sent) + len(received) == len(records)
    assert {m.get_srcSystem() for m, _ in sent} == {1}  # the vehicle
    assert {m.get_srcSystem() for m, _ in received} == {255}  # the ground station
    sent_types = {m.get_type() for m, _ in sent}
    assert {"HEARTBEAT", "GLOBAL_POSITION_INT", "ATTITUDE", "VFR_HUD", "MISSION_ACK"} <= sent_types
    assert any(m.get_type() == "HEARTBEAT" and m.type == mavutil.mavlink.MAV_TYPE_FIXED_WING
               for m, _ in sent)
    # What the ground station sent: its HEARTBEATs and the HiL's mission upload, item by item.
    plan = mission.read_wpl(os.path.join(ROOT, "aircraft", "DG808", "missions", "case_study.waypoints"))
    counts = [m for m, _ in received if m.get_type() == "MISSION_COUNT"]
    assert counts and all(c.count == len(plan.items) for c in counts), counts
    items = {m.seq: m for m, _ in received if m.get_type() == "MISSION_ITEM_INT"}
    assert sorted(items) == list(range(len(plan.items)))
    for seq, it in enumerate(plan.items):
        assert (items[seq].x, items[seq].y) == (int(round(it.lat_deg * 1e7)), int(round(it.lon_deg * 1e7)))
    assert any(m.get_type() == "HEARTBEAT" and m.type == mavutil.mavlink.MAV_TYPE_GCS for m, _ in received)
    # The vehicle's position is the flight's: near home, not zero.
    home_lat, home_lon, _ = plan.home
    positions = [m for m, _ in sent if m.get_type() == "GLOBAL_POSITION_INT"]
    assert all(abs(p.lat * 1e-7 - home_lat) < 0.05 and abs(p.lon * 1e-7 - home_lon) < 0.05 for p in positions)
    # Wall-clock microseconds since the Unix epoch, in order, spanning the flight: the node runs
    # from before the simulator's loop (wall_s of it) to after it; its last record is written
    # before the file's last change.
    times = [t for _, t, _ in records]
    assert all(b >= a for a, b in zip(times, times[1:]))
    written_s = os.path.getmtime(path)
    # Before the loop: the master, the launch, the mission upload (a few seconds; 120 s is lenient).
    assert written_s - s["wall_s"] - 120.0 <= times[0] and times[-1] <= written_s + 0.01, (times[0], times[-1], written_s)
    span_s = times[-1] - times[0]
    assert s["wall_s"] <= span_s <= s["wall_s"] + 120.0, (span_s, s["wall_s"])
