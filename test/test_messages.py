"""The message interface seen from Python (rospy, the HiL tools, the ground-station tests):
round trips keep every field and the md5sums match the pinned ones, as in C++."""
import io
import math
import zlib
from pathlib import Path

import pytest

from drone_ros import msg as drone_msgs

PINNED = Path(__file__).with_name("message_md5sums.txt")


def pinned_md5sums():
    sums = {}
    for line in PINNED.read_text().splitlines():
        if line and not line.startswith("#"):
            name, md5 = line.split()
            assert name not in sums, "%s pinned twice in %s" % (name, PINNED.name)
            sums[name] = md5
    return sums


def round_trip(message):
    buf = io.BytesIO()
    message.serialize(buf)
    raw = buf.getvalue()
    back = type(message)()
    back.deserialize(raw)
    again = io.BytesIO()
    back.serialize(again)
    assert again.getvalue() == raw
    return raw, back


def test_servo_command_round_trip_keeps_every_field():
    cmd = drone_msgs.ServoCommand(
        seq=4000000123, throttle=0.62, elevator_deg=-19.5, aileron_deg=14.25, rudder_deg=-3.0,
        alpha_est_deg=4.5, beta_est_deg=-1.25, estimator_converged=True,
        sensor_links_healthy=False, crc32=0xDEADBEEF)
    cmd.stamp.secs, cmd.stamp.nsecs = 1700000000, 123456789
    raw, back = round_trip(cmd)
    assert len(raw) == 42
    assert back.seq == 4000000123
    assert (back.stamp.secs, back.stamp.nsecs) == (1700000000, 123456789)
    assert back.elevator_deg == pytest.approx(-19.5)
    assert back.aileron_deg == pytest.approx(14.25)
    assert back.beta_est_deg == pytest.approx(-1.25)
    assert back.estimator_converged and not back.sensor_links_healthy
    assert back.crc32 == 0xDEADBEEF


def test_decision_status_round_trip_keeps_reasons():
    status = drone_msgs.DecisionStatus(
        controller=drone_msgs.DecisionStatus.CONTROLLER_HA,
        reasons=drone_msgs.DecisionStatus.REASON_NOT_FINITE | drone_msgs.DecisionStatus.REASON_FROZEN,
        restart_count=3, restart_requested=True, altitude_agl_ft=401.0, state_region_max=1.3)
    _, back = round_trip(status)
    assert back.controller == drone_msgs.DecisionStatus.CONTROLLER_HA
    assert back.reasons == 4 | 512
    assert back.restart_count == 3 and back.restart_requested
    assert back.altitude_agl_ft == pytest.approx(401.0)


def test_operator_command_round_trip_keeps_the_request_and_its_id():
    cmd = drone_msgs.OperatorCommand(command=drone_msgs.OperatorCommand.RESTART_HP,
                                     request_id=4000000001)
    cmd.stamp.secs, cmd.stamp.nsecs = 1700000000, 5
    cmd.crc32 = 0xCAFEF00D
    raw, back = round_trip(cmd)
    assert len(raw) == 42  # the Due decodes it by position: 38 bytes of fields, then crc32
    assert back.crc32 == 0xCAFEF00D
    assert back.command == drone_msgs.OperatorCommand.RESTART_HP
    assert back.request_id == 4000000001
    assert (back.stamp.secs, back.stamp.nsecs) == (1700000000, 5)


def test_operator_set_home_keeps_the_position_in_full_double_precision():
    cmd = drone_msgs.OperatorCommand(command=drone_msgs.OperatorCommand.SET_HOME, request_id=9,
                                     latitude=40.4237054, longitude=-86.9211946, altitude=185.25)
    _, back = round_trip(cmd)
    assert (back.command, back.use_current) == (5, False)
    assert (back.latitude, back.longitude, back.altitude) == (40.4237054, -86.9211946, 185.25)


def test_home_position_round_trip_keeps_full_double_precision():
    home = drone_msgs.HomePosition(seq=2, latitude=40.4237054, longitude=-86.9211946, altitude=185.25)
    raw, back = round_trip(home)
    assert len(raw) == 8 + 4 + 3 * 8
    assert (back.seq, back.latitude, back.longitude, back.altitude) == (2, 40.4237054, -86.9211946, 185.25)


def test_way_carries_32_waypoints():
    way = drone_msgs.way(north=[float(i) for i in range(32)], east=[-1.0] * 32,
                         height=[300.0] * 32, velocity=[60.0] * 32, fp=32)
    _, back = round_trip(way)
    assert list(back.north) == [float(i) for i in range(32)]
    assert back.fp == 32


def test_data_round_trip_keeps_estimates():
    data = drone_msgs.data()
    data.angle.x = 0.1
    data.wind_est = [1.0, 2.0, 3.0]
    data.mw_north = [float(i) for i in range(6)]
    data.alphaest = math.radians(4.0)
    _, back = round_trip(data)
    assert list(back.wind_est) == [1.0, 2.0, 3.0]
    assert back.mw_north[5] == 5.0
    assert back.alphaest == pytest.approx(math.radians(4.0))


@pytest.mark.parametrize("name", ["DecisionStatus", "HilTruth", "HomePosition", "LockstepStep", "OperatorCommand", "ServoCommand", "data", "hil_data", "ins", "pwm", "way"])
def test_md5sum_is_pinned(name):
    cls = getattr(drone_msgs, name)
    assert pinned_md5sums()[cls._type] == cls._md5sum, (
        f"{cls._type} changed; the Due firmware depends on it: regenerate and re-pin deliberately")


def test_operator_command_crc_is_zlib_crc32_over_the_first_38_bytes():
    """What a sender (microhard_gs, a Python tool) must do to make a request the HA acts on."""
    cmd = drone_msgs.OperatorCommand(command=drone_msgs.OperatorCommand.SET_HOME, request_id=9,
                                     latitude=40.4237054, longitude=-86.9211946, altitude=185.25)
    raw, _ = round_trip(cmd)
    cmd.crc32 = zlib.crc32(raw[:38])
    raw2, back = round_trip(cmd)
    assert raw2[:38] == raw[:38]
    assert raw2[38:] == cmd.crc32.to_bytes(4, "little")
    assert back.crc32 == zlib.crc32(raw2[:38])


def test_servo_command_crc_is_zlib_crc32_over_the_first_38_bytes():
    """What a Python tool (HiL, fault injection) must do to make a command the HA accepts."""
    cmd = drone_msgs.ServoCommand(seq=77, throttle=0.55, elevator_deg=-2.5, aileron_deg=7.0)
    raw, _ = round_trip(cmd)
    cmd.crc32 = zlib.crc32(raw[:38])
    raw2, back = round_trip(cmd)
    assert raw2[:38] == raw[:38]
    assert back.crc32 == zlib.crc32(raw2[:38])
