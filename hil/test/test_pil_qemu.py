"""Processor in the loop: the HA firmware as Cortex-M3 machine code on QEMU's mps2-an385
(arduino_ha/pil, hil/ha_qemu.py's QemuBoard), driven the way the simulator drives it: control
records on its third UART, the simulator's VN-200 bytes on its second, rosserial frames from a
host on its first (the HP link), stepped on simulation time. Only ptys; QEMU is stopped after
each story. test_ha_channel.py runs the SIL's stories on this board too."""
import os
import struct
import sys
import tempfile
import zlib

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
sys.path.insert(0, ROOT)
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "drone_ros", "arduino_link", "test"))
from hil import ha_channel, ha_qemu, sensors  # noqa: E402
from wire_tap import frame, split_frames  # noqa: E402
from ha_in_loop import Parked, build_pil_image  # noqa: E402

HA, MANUAL, HP = 1, 4, 0
CIC, PIC = (1100, 1500, 1500, 1500, 1000), (1100, 1800, 1500, 1500, 2000)
SUBSCRIBER_INFO = 1  # rosserial's topic id of a device's subscriber announcement


@pytest.fixture(scope="module")
def image(tmp_path_factory):
    return build_pil_image(str(tmp_path_factory.mktemp("pil")))


class Rig:
    def __init__(self, image):
        d = tempfile.mkdtemp(prefix="pil_")
        self.vn = sensors.Vn200Port(os.path.join(d, "ha_vn200"), 1, seed=7,
                                    baud=sensors.HA_VN200_BAUD, fixed_output=sensors.HA_OUTPUT_1)
        self.board = ha_qemu.QemuBoard(image, os.path.join(d, "ha_vn200")).start()
        self.host = ha_qemu.raw_open(self.board.hp_pty)  # the HP's end of the rosserial link
        self.from_ha = bytearray()

    def step(self, k, rc=CIC, wait_for=None, wait_ms=2000):
        self.vn.emit_until(k * 0.01, lambda t: Parked)
        rec = self.record(k, rc, wait_for, wait_ms)
        reply, dropped, ticks = self.board.exchange(rec)
        return ha_channel.decode_reply(reply), dropped, ticks

    def record(self, k, rc=CIC, wait_for=None, wait_ms=2000):
        flags = ha_channel.RC_VALID | ha_channel.AIRSPEED_OK | ha_channel.BATTERY_OK | \
            (ha_channel.WAIT_COMMAND if wait_for is not None else 0)
        return ha_channel.STEP.pack(ha_channel.MAGIC_STEP, ha_channel.VERSION, flags, k * 10000,
                                    self.vn.pty.written, wait_for or 0, wait_ms, *rc, 0, 0.0, 12.4)

    def frames_from_ha(self):
        try:
            while True:
                self.from_ha += os.read(self.host, 4096)
        except BlockingIOError:
            pass
        return split_frames(self.from_ha)

    def close(self):
        os.close(self.host)
        self.board.stop()
        self.vn.close()


@pytest.fixture
def rig(image):
    r = Rig(image)
    yield r
    r.close()


def servo_command(seq, elevator_deg):
    fields = struct.pack("<III6fBB", seq, 1700000000, seq * 10000000 % 1000000000, 0.0, elevator_deg,
                         1.5, -0.5, 2.0, 0.0, 1, 1)
    return fields + struct.pack("<I", zlib.crc32(fields))


def negotiate(rig, k):
    """The host's topic request; returns the topic id the HA takes ServoCommands on."""
    os.write(rig.host, frame(0, b""))
    for k in range(k, k + 50):
        rig.step(k)
        for f in rig.frames_from_ha():
            topic = f[5] | f[6] << 8
            if topic == SUBSCRIBER_INFO and b"drone_ros/ServoCommand" in f:
                return f[7] | f[8] << 8, k + 1
    raise AssertionError("the HA never announced its ServoCommand subscriber")


def test_with_no_hp_command_the_ha_flies_its_own_command_out_to_the_servos(rig):
    for k in range(60):
        r, dropped, _ = rig.step(k)
    assert r.controller == HA
    assert r.flags & ha_channel.R_STATE_VALID  # its own VN-200, through its own UART
    assert r.vn_bytes_read == rig.vn.pty.written
    assert r.applied == r.ha_command  # the safety controller's command is what the servos get
    assert r.commands_received == 0 and dropped == 0


def test_valid_servo_commands_from_the_hp_reach_the_servos(rig):
    topic, k = negotiate(rig, 0)
    seq, hp_periods = 0, 0
    for k in range(k, k + 800):
        seq += 1
        os.write(rig.host, frame(topic, servo_command(seq, -2.5)))
        r, _, _ = rig.step(k, wait_for=seq)
        assert not r.flags & ha_channel.R_COMMAND_TIMEOUT
        hp_periods = hp_periods + 1 if r.controller == HP else 0
        if hp_periods == 200:  # past the switch's rate-limited (bumpless) slew
            break
    assert r.controller == HP, "the HA never handed the servos to a healthy HP (%d)" % r.controller
    assert r.commands_received == seq and r.last_seq == seq
    assert r.applied[0] == pytest.approx(-2.5) and r.applied[1] == pytest.approx(1.5)
    assert r.applied[0] != pytest.approx(r.ha_command[0])


def test_a_control_record_failing_its_crc_is_counted_and_dropped_never_applied(rig):
    for k in range(20):
        r, dropped, _ = rig.step(k)
    assert r.controller == HA and dropped == 0
    # The pilot's switch in a record one bit of which the line flipped: never the pilot's servos.
    bad = bytearray(ha_qemu.frame(rig.record(20, rc=PIC)))
    bad[30] ^= 0x04
    rig.board.write_raw(bad)
    r, dropped, _ = rig.step(21)
    assert dropped == 1
    assert r.t_us == 210000  # the reply is the good record's: the bad one got none
    assert r.controller == HA
    # The same record intact is applied (the pilot takes the servos): the drop was the CRC's doing.
    for k in range(22, 40):
        r, dropped, _ = rig.step(k, rc=PIC)
    assert r.controller == MANUAL and dropped == 1


def test_a_control_frame_of_impossible_length_is_counted_and_the_next_frame_still_found(rig):
    r, _, _ = rig.step(0)
    rig.board.write_raw(ha_qemu.SYNC + b"\xff\x7f" + bytes(10))
    r, dropped, _ = rig.step(1)
    assert dropped == 1 and r.t_us == 10000 and r.flags & ha_channel.R_STEPPED
