"""flight_report on the bag of a real lockstep HiL flight with a fault (hil/run_flight.py records
it and runs the report, as `make run` does): every figure is drawn and on the page, and the
page's switch list is the flight's switches as the simulator saw them on the servos (summary.json
"who_flew", from the HA's replies in the loop), not as the report read them from the bag."""
import os
import sys

import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from test_flight_report import FIGURES, page, png_size  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "hil", "faults", "test"))
from flight import fly  # noqa: E402  (the fault tests' flights, each flown once per test run)
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
