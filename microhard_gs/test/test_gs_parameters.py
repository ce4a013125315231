"""PARAM_SET from a real MAVLink client (pymavlink) reaches the real controller_DG808 through
microhard_gs and its ~set_tunable: the echo is the value the controller flies with, a refused
value is echoed back as the old one with a STATUSTEXT saying why."""
import os
import struct
import time

import pytest
import yaml

from stack_testing import gs_harness as gh  # noqa: E402
from stack_testing.gs_harness import mavlink  # noqa: E402

HP, HA = 0, 1


@pytest.fixture(scope="module")
def gs():
    system = gh.GsSystem(controller=True)
    yield system
    system.stop()


def set_param(gs, param_id, value, param_type=mavlink.MAV_PARAM_TYPE_REAL32):
    if param_type == mavlink.MAV_PARAM_TYPE_INT32:
        value = struct.unpack("<f", struct.pack("<i", value))[0]  # byte-wise, as advertised
    gs.conn.mav.param_set_send(1, 1, param_id.encode(), value, param_type)
    echo = gh.wait_param_value(gs.conn, param_id)
    assert echo is not None, "no PARAM_VALUE echo for %s" % param_id
    return gh.param_value(echo)


def controller_diagnostic(gs, key, predicate, timeout=10.0):
    event = gs.wait_event(lambda e: e["topic"] == "controller_diagnostics" and predicate(e["values"].get(key)),
                          timeout)
    return None if event is None else event["values"].get(key)


def fly_on(gs, controller):
    """Tells the controller (and microhard_gs) who flies, and gives /decision_status time to land."""
    gs.send_decision(controller, 0)
    assert gs.wait_event(lambda e: e["topic"] == "decision_sent", 5) is not None
    time.sleep(1.0)


def test_valid_gain_is_echoed_as_the_new_value_and_the_controller_flies_with_it(gs):
    assert set_param(gs, "KpLon", 0.005) == pytest.approx(0.005)
    assert float(gs.rosparam("/controller_DG808/KpLon")) == pytest.approx(0.005)  # written by the controller
    assert controller_diagnostic(gs, "tunables_changed", lambda v: v is not None and int(v) >= 1) is not None


def whole_statustext(conn, first, timeout_s=2.0):
    """A STATUSTEXT and the chunks after it that share its id (MAVLink 2 splits long texts in
    50-character chunks), joined."""
    chunks = {first.chunk_seq: first.text}
    deadline = time.time() + timeout_s
    while first.id and len(chunks[max(chunks)]) == 50 and time.time() < deadline:
        st = conn.recv_match(type="STATUSTEXT", blocking=True, timeout=0.2)
        if st is not None and st.id == first.id:
            chunks[st.chunk_seq] = st.text
    return "".join(chunks[k] for k in sorted(chunks))


def test_out_of_range_value_is_echoed_as_the_old_one_with_the_reason(gs):
    assert set_param(gs, "mpf_radius", -5.0) == pytest.approx(250.0)
    text = gh.wait_statustext(gs.conn, "mpf_radius")
    assert text is not None and "refused" in text.text
    # The range and units of aircraft/DG808/tunables.yaml, through the controller's check.
    assert whole_statustext(gs.conn, text).endswith("mpf_radius = -5 is outside [20, 5000] ft")
    # The reason is the controller's own check, the one the aircraft file meets.
    assert controller_diagnostic(gs, "tunables_refused", lambda v: v is not None and int(v) >= 1) is not None
    assert float(gs.rosparam("/controller_DG808/mpf_radius")) == pytest.approx(250.0)


def test_rate_and_lqr_weight_cannot_change_in_flight_and_the_operator_learns_why(gs):
    assert set_param(gs, "Q_weight", 99.0) == pytest.approx(1.0)
    assert gh.wait_statustext(gs.conn, "Q_weight refused") is not None
    assert set_param(gs, "dt", 0.02) == pytest.approx(0.01)
    assert gh.wait_statustext(gs.conn, "dt refused") is not None


def test_switch_is_set_byte_wise_and_the_controller_keeps_it_an_integer(gs):
    assert set_param(gs, "path_select", 1, mavlink.MAV_PARAM_TYPE_INT32) == 1
    assert gs.rosparam("/controller_DG808/path_select") == "1"


def test_every_parameter_served_is_a_tunable_the_controller_knows(gs):
    """The ground station's table and the controller's ~set_tunable are one list
    (aircraft/DG808/tunables.yaml): all of it is served, and a set of each served parameter to
    the value it has reaches a controller that knows the name (it refuses names it does not know
    as "not a tunable"; dt and Q_weight it refuses as fixed)."""
    with open(os.path.join(gh.AIRCRAFT_DIR, "tunables.yaml")) as f:
        listed = {t.get("mav_id", t["name"]) for t in yaml.safe_load(f)["tunables"]}
    fly_on(gs, HA)
    gs.conn.mav.param_request_list_send(1, 1)
    served = {}
    count = None
    deadline = time.time() + 15
    while time.time() < deadline and (count is None or len(served) < count):
        m = gs.conn.recv_match(type="PARAM_VALUE", blocking=True, timeout=0.5)
        if m is not None:
            count = m.param_count
            served[m.param_id] = m
    assert set(served) == listed and count == len(listed)
    texts = []
    for param_id, m in sorted(served.items()):
        gs.conn.mav.param_set_send(1, 1, param_id.encode(), m.param_value, m.param_type)
        deadline = time.time() + 5
        echo = None
        while time.time() < deadline and echo is None:
            msg = gs.conn.recv_match(type=["PARAM_VALUE", "STATUSTEXT"], blocking=True, timeout=0.2)
            if msg is not None and msg.get_type() == "STATUSTEXT":
                texts.append(msg.text)
            elif msg is not None and msg.param_id == param_id:
                echo = msg
        assert echo is not None and echo.param_value == m.param_value, param_id
    deadline = time.time() + 1.0  # the reason follows the last echo
    while time.time() < deadline:
        msg = gs.conn.recv_match(type="STATUSTEXT", blocking=True, timeout=0.2)
        if msg is not None:
            texts.append(msg.text)
    joined = "".join(texts)  # long reasons come in 50-character chunks, in order
    assert "not a tunable" not in joined and "not running" not in joined, texts


def test_gain_change_waits_for_the_ha_to_fly_but_a_trim_goes_in_at_once(gs):
    fly_on(gs, HP)
    assert set_param(gs, "KiLon", 0.001) == pytest.approx(0.0008)
    assert gh.wait_statustext(gs.conn, "select the HA") is not None
    assert set_param(gs, "elevator_trim", 0.01) == pytest.approx(0.01)
    fly_on(gs, HA)
    assert set_param(gs, "KiLon", 0.001) == pytest.approx(0.001)
