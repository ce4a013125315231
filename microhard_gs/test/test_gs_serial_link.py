"""The Microhard modem's side: microhard_gs on a serial port (a pseudo-terminal standing in for
the modem, reached through a symlink as udev's by-id name reaches the real one) is the same
vehicle to a ground station as over UDP, and a modem missing at start or unplugged in flight is
an outage the node waits out, never its end."""
import os
import select
import tempfile
import time
import tty

import pytest

from stack_testing import gs_harness as gh  # noqa: E402
from stack_testing.gs_harness import mavlink  # noqa: E402


class Sink:
    def write(self, _):
        pass


class Modem:
    """A pty behind a fixed name; plug() makes a new one (a re-plugged modem gets a new pts)."""

    def __init__(self, link):
        self.link = link
        self.master = self.slave = None

    def plug(self):
        self.master, self.slave = os.openpty()
        tty.setraw(self.master)
        tmp = self.link + ".new"
        os.symlink(os.ttyname(self.slave), tmp)
        os.replace(tmp, self.link)  # atomic: the node never sees a half-made name

    def unplug(self):
        # udev removes the by-id name first: a name left pointing at a freed pts could reach
        # whatever pty another process opens next under that number.
        if os.path.lexists(self.link):
            os.unlink(self.link)
        for fd in (self.master, self.slave):
            if fd is not None:
                os.close(fd)
        self.master = self.slave = None

    def close(self):
        self.unplug()


@pytest.fixture(scope="module")
def bench():
    """The ROS master, the aircraft's parameters and the probe, shared by the module's tests."""
    system = gh.GsSystem(udp_client=False, node=False)
    try:
        yield system
    finally:
        system.stop()


@pytest.fixture
def modem(bench):
    """A node of its own for each test (started before its modem exists), so no test depends on
    what an earlier one plugged or counted."""
    tmpdir = tempfile.mkdtemp(prefix="gs_modem_")
    device = Modem(os.path.join(tmpdir, "microhard"))
    try:
        # The node starts before the modem exists, as when the radio enumerates late.
        bench.start_node({"transport": "serial", "serial_port": device.link, "serial_baud": 57600,
                          "reopen_period_s": 0.2})
        yield bench, device
    finally:
        if bench.launch is not None:
            bench.stop_node()
        device.close()
        os.rmdir(tmpdir)


def read_messages(fd, parser, seconds, wanted=None):
    out = []
    deadline = time.time() + seconds
    while time.time() < deadline:
        ready, _, _ = select.select([fd], [], [], 0.1)
        if not ready:
            continue
        try:
            chunk = os.read(fd, 4096)
        except OSError:  # EIO until the node has the slave open
            time.sleep(0.05)
            continue
        for m in parser.parse_buffer(chunk) or []:
            out.append(m)
            if wanted is not None and m.get_type() == wanted:
                return out
    return out


def heartbeats(fd, seconds=30):
    gcs = mavlink.MAVLink(Sink(), srcSystem=255, srcComponent=190)
    return [m for m in read_messages(fd, gcs, seconds, wanted="HEARTBEAT") if m.get_type() == "HEARTBEAT"]


def test_modem_missing_at_start_is_reported_and_the_node_keeps_running(modem):
    system, _ = modem
    assert system.wait_diagnostic("link_up", lambda v: v == "false") == "false"
    assert int(system.wait_diagnostic("link_open_failures", lambda v: int(v) >= 1)) >= 1
    # telemetry dropped and counted
    assert int(system.wait_diagnostic("frames_not_sent_link_down", lambda v: int(v) > 0)) > 0
    assert system.launch.poll() is None


def test_modem_appearing_later_gets_the_heartbeat_and_the_parameters(modem):
    system, device = modem
    device.plug()
    hb = heartbeats(device.master)
    assert hb and hb[0].type == mavlink.MAV_TYPE_FIXED_WING
    gcs = mavlink.MAVLink(Sink(), srcSystem=255, srcComponent=190)
    os.write(device.master, gcs.param_request_read_encode(1, 1, b"VTtrim", -1).pack(gcs))
    values = [m for m in read_messages(device.master, gcs, 5, wanted="PARAM_VALUE") if m.get_type() == "PARAM_VALUE"]
    assert values and values[0].param_id == "VTtrim" and values[0].param_value == pytest.approx(60.0)
    assert system.wait_diagnostic("link_up", lambda v: v == "true") == "true"


def test_unplugged_modem_is_an_outage_and_the_replugged_one_resumes_in_the_same_process(modem):
    system, device = modem
    device.plug()
    assert heartbeats(device.master), "no HEARTBEAT from the first modem"
    assert system.wait_diagnostic("link_opens", lambda v: int(v) == 1) == "1"
    device.unplug()
    assert system.wait_diagnostic("link_outages", lambda v: int(v) == 1) == "1"
    assert system.wait_diagnostic("link_up", lambda v: v == "false") == "false"
    device.plug()
    assert heartbeats(device.master), "no HEARTBEAT after the modem came back"
    # Counters carried across the outage: the same process reopened, nothing respawned it.
    assert system.wait_diagnostic("link_opens", lambda v: int(v) == 2) == "2"
    assert int(system.diagnostic("link_outages")) == 1
    assert system.launch.poll() is None
