"""The Microhard modem's side: microhard_gs on a serial port (a pseudo-terminal standing in for
the modem) is the same vehicle to a ground station as over UDP."""
import os
import select
import sys
import time
import tty

import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gs_harness as gh  # noqa: E402
from gs_harness import mavlink  # noqa: E402


class Sink:
    def write(self, _):
        pass


@pytest.fixture(scope="module")
def modem():
    master, slave = os.openpty()
    tty.setraw(master)
    name = os.ttyname(slave)
    system = gh.GsSystem(launch_args={"transport": "serial", "serial_port": name, "serial_baud": 57600},
                         udp_client=False)
    yield system, master
    system.stop()
    os.close(slave)
    os.close(master)


def read_messages(fd, parser, seconds, wanted=None):
    out = []
    deadline = time.time() + seconds
    while time.time() < deadline:
        ready, _, _ = select.select([fd], [], [], 0.1)
        if not ready:
            continue
        for m in parser.parse_buffer(os.read(fd, 4096)) or []:
            out.append(m)
            if wanted is not None and m.get_type() == wanted:
                return out
    return out


def test_vehicle_heartbeat_and_parameters_over_the_serial_link(modem):
    system, fd = modem
    gcs = mavlink.MAVLink(Sink(), srcSystem=255, srcComponent=190)
    msgs = read_messages(fd, gcs, 10, wanted="HEARTBEAT")
    heartbeats = [m for m in msgs if m.get_type() == "HEARTBEAT"]
    assert heartbeats and heartbeats[0].type == mavlink.MAV_TYPE_FIXED_WING
    os.write(fd, gcs.param_request_read_encode(1, 1, b"VTtrim", -1).pack(gcs))
    values = [m for m in read_messages(fd, gcs, 5, wanted="PARAM_VALUE") if m.get_type() == "PARAM_VALUE"]
    assert values and values[0].param_id == "VTtrim" and values[0].param_value == pytest.approx(60.0)
