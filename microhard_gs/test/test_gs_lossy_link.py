"""A mission upload over a link that loses 20% of the datagrams each way still completes,
through the protocol's timeouts and retries on both sides."""

import pytest

from stack_testing import gs_harness as gh  # noqa: E402
from stack_testing.gs_harness import mavlink  # noqa: E402


@pytest.fixture(scope="module")
def lossy_gs():
    # A short item timeout keeps the test quick; the retry logic is the same as with the
    # aircraft's 1.5 s.
    system = gh.GsSystem(launch_args={"mission_item_timeout_s": 0.3}, relay_loss=0.2)
    yield system
    system.stop()


def test_ten_waypoint_upload_under_20_percent_loss_succeeds_through_retries(lossy_gs):
    gs = lossy_gs
    items = [gh.waypoint(i, 150.0 * i, -60.0 * (i % 4), 180.0 + 5.0 * i) for i in range(10)]
    ack = None
    for _ in range(3):  # the final ACK itself may be lost; the GCS then repeats, as QGC does
        ack = gh.upload_mission(gs.conn, items, resend_s=0.5, timeout_s=30)
        if ack is not None and ack.type == mavlink.MAV_MISSION_ACCEPTED:
            break
    assert ack is not None and ack.type == mavlink.MAV_MISSION_ACCEPTED
    event = gs.wait_event(lambda e: e["topic"] == "way" and e["fp"] == 10, 10)
    assert event is not None
    for i in range(10):
        assert event["north"][i] == pytest.approx(150.0 * i, abs=0.5)
        assert event["height"][i] == pytest.approx(180.0 + 5.0 * i, abs=0.01)
    assert gs.relay.dropped > 0, "the relay dropped nothing: the test proved nothing"
    # Each request and its answer both survive with probability 0.8 * 0.8; with 20 tries per
    # request, a download of 11 requests fails by chance once in ~10^8 runs, so a failure here is
    # the node's, and the message says where it stopped.
    gave_up = []
    downloaded = gh.download_mission(gs.conn, timeout_s=0.5, attempts=20, gave_up=gave_up)
    assert downloaded is not None and len(downloaded) == 10, \
        "download gave up waiting for %s (relay forwarded %d, dropped %d)" % (
            gave_up, gs.relay.forwarded, gs.relay.dropped)
