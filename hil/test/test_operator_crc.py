"""The HiL's CRC of a message ending in crc32 (hil/faults/base.py, fields_crc32) is the CRC the HA
checks: zlib's crc32 over the message's ROS serialization before crc32, equal to the C side's
(common/src/hp_command.c, as the build links it into libstack_common.so) for an
OperatorCommand and for a ServoCommand packed by the C itself."""
import ctypes
import io
import zlib

import pytest
from drone_ros.msg import OperatorCommand, ServoCommand
from stack_common import native

from hil.faults.base import fields_crc32


class HaHpCommand(ctypes.Structure):
    """common/src/hp_command.h's struct, what ha_hp_command_compute_crc packs itself."""
    _fields_ = [("seq", ctypes.c_uint32), ("stamp_sec", ctypes.c_uint32), ("stamp_nsec", ctypes.c_uint32),
                ("throttle", ctypes.c_float), ("elevator_deg", ctypes.c_float), ("aileron_deg", ctypes.c_float),
                ("rudder_deg", ctypes.c_float), ("alpha_est_deg", ctypes.c_float), ("beta_est_deg", ctypes.c_float),
                ("estimator_converged", ctypes.c_uint8), ("sensor_links_healthy", ctypes.c_uint8),
                ("crc32", ctypes.c_uint32)]


@pytest.fixture(scope="module")
def c_side():
    so = native.load("libstack_common.so")  # a handle of its own: the prototypes below are this test's
    so.ha_crc32.restype = ctypes.c_uint32
    so.ha_crc32.argtypes = [ctypes.c_char_p, ctypes.c_size_t]
    so.ha_hp_command_compute_crc.restype = ctypes.c_uint32
    so.ha_hp_command_compute_crc.argtypes = [ctypes.POINTER(HaHpCommand)]
    return so


def serialized(msg):
    raw = io.BytesIO()
    msg.serialize(raw)
    return raw.getvalue()


def test_hil_operator_crc_is_the_crc_the_ha_checks():
    cmd = OperatorCommand(command=OperatorCommand.SET_HOME, request_id=4000000001, use_current=False,
                          latitude=40.4237054, longitude=-86.9211946, altitude=185.25)
    cmd.stamp.secs, cmd.stamp.nsecs = 1700000000, 5
    raw = serialized(cmd)
    assert len(raw) == 42
    assert fields_crc32(cmd) == zlib.crc32(raw[:38])
    cmd.command = OperatorCommand.SELECT_HP
    assert fields_crc32(cmd) != zlib.crc32(raw[:38])


def test_hil_operator_crc_equals_the_c_sides(c_side):
    # The HA's link checks ha_crc32 over HA_OPERATOR_COMMAND_FIELDS_LEN (38) serialized bytes.
    cmd = OperatorCommand(command=OperatorCommand.SELECT_HA, request_id=0xFFFFFFFF, use_current=True,
                          latitude=-33.5, longitude=151.25, altitude=-12.0)
    cmd.stamp.secs, cmd.stamp.nsecs = 1800000000, 999999999
    assert fields_crc32(cmd) == c_side.ha_crc32(serialized(cmd), 38)


def test_hil_servo_command_crc_equals_the_c_sides_over_the_c_sides_own_packing(c_side):
    for seq, throttle, surfaces, converged, healthy in (
            (7, 0.45, (-1.0, 2.5, 0.5, 4.0, -0.75), True, True),
            (0xFFFFFFF0, 1.0, (20.0, -15.0, 15.0, -30.0, 30.0), False, True),
            (0, 0.0, (1e-7, -3.4e38, 3.4e38, float("nan"), float("-inf")), True, False)):
        msg = ServoCommand(seq=seq, throttle=throttle, elevator_deg=surfaces[0], aileron_deg=surfaces[1],
                           rudder_deg=surfaces[2], alpha_est_deg=surfaces[3], beta_est_deg=surfaces[4],
                           estimator_converged=converged, sensor_links_healthy=healthy, crc32=0xA5A5A5A5)
        msg.stamp.secs, msg.stamp.nsecs = 1700000000 + seq % 7, 123456789
        ha = HaHpCommand(seq, msg.stamp.secs, msg.stamp.nsecs, throttle, *surfaces, converged, healthy, 0)
        assert fields_crc32(msg) == c_side.ha_hp_command_compute_crc(ctypes.byref(ha)), "seq %d" % seq


def test_a_message_without_a_trailing_crc32_is_refused():
    from drone_ros.msg import pwm
    with pytest.raises(ValueError):
        fields_crc32(pwm())
