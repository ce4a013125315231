"""Processor in the loop: the HA firmware as Cortex-M3 machine code on QEMU's mps2-an385
(arduino_ha/pil, hil/ha_qemu.py's QemuBoard), driven the way the simulator drives it: control
records on its third UART, the simulator's VN-200 bytes on its second, rosserial frames from a
host on its first (the HP link), stepped on simulation time. Only ptys and QEMU's unix sockets;
QEMU is stopped after each story. test_ha_channel.py runs the SIL's stories on this board too."""
import os

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
from hil import ha_channel, record_bridge  # noqa: E402
from stack_testing.wire_tap import frame  # noqa: E402
from stack_testing.ha_in_loop import (HA, HP, MANUAL, PIC, PilRig, build_pil_image, negotiate,  # noqa: E402
                        servo_command)


@pytest.fixture(scope="module")
def image(tmp_path_factory):
    return build_pil_image(str(tmp_path_factory.mktemp("pil")))


@pytest.fixture
def rig(image):
    r = PilRig(image)
    yield r
    r.close()


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
    bad = bytearray(record_bridge.frame(rig.record(20, rc=PIC)))
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
    rig.board.write_raw(record_bridge.SYNC + b"\xff\x7f" + bytes(10))
    r, dropped, _ = rig.step(1)
    assert dropped == 1 and r.t_us == 10000 and r.flags & ha_channel.R_STEPPED
