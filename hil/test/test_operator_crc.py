"""The HiL's own packing of msg/OperatorCommand.msg's CRC (hil/faults/base.py, operator_crc32) is
the CRC the HA checks: zlib crc32 over the message's ROS serialization before crc32."""
import io
import os
import sys
import zlib

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, ROOT)
from hil.faults.base import operator_crc32  # noqa: E402
from drone_ros.msg import OperatorCommand  # noqa: E402


def test_hil_operator_crc_is_the_crc_over_the_serialized_fields():
    cmd = OperatorCommand(command=OperatorCommand.SET_HOME, request_id=4000000001, use_current=False,
                          latitude=40.4237054, longitude=-86.9211946, altitude=185.25)
    cmd.stamp.secs, cmd.stamp.nsecs = 1700000000, 5
    raw = io.BytesIO()
    cmd.serialize(raw)
    assert len(raw.getvalue()) == 42
    assert operator_crc32(cmd) == zlib.crc32(raw.getvalue()[:38])
    cmd.command = OperatorCommand.SELECT_HP
    assert operator_crc32(cmd) != zlib.crc32(raw.getvalue()[:38])
