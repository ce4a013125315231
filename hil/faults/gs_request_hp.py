"""A ground station asks for the HP while it is failing: the HP's commands carry NaN in a surface
(params surface, default aileron) for the window, and from request_after_s (default 0.5) after
at_s, every request_every_s (default 2.0), a MAVLink COMMAND_LONG DO_SET_MODE (custom mode 0,
the HP) goes to microhard_gs over UDP loopback, as QGroundControl sends it. Time stands until the
COMMAND_ACK is back and /operator_command has carried the request on, sealed with the CRC-32 the
HA checks (one without it the HA drops, and the fault would test nothing). The HA must keep the
failing HP off the servos. Took effect when the NaN commands reached the HA and at least one
request was accepted (forwarded) and seen sealed on /operator_command."""
import time

from pymavlink import mavutil

from hil.faults.base import SURFACES, fields_crc32
from hil.faults.nan import Nan


class GsRequestHp(Nan):
    def __init__(self, *a):
        super().__init__(*a)
        import rospy
        from drone_ros.msg import OperatorCommand
        self.forwarded = 0
        rospy.Subscriber("operator_command", OperatorCommand, self.on_operator, queue_size=10)
        self.next_request_s = self.at_s + self.param("request_after_s", 0.5)
        self.acks = []
        self.link = None

    def on_operator(self, msg):
        if msg.command == 1 and msg.crc32 == fields_crc32(msg):  # SELECT_HP, as the HA takes it
            self.forwarded += 1

    def on_step(self, t_s):
        if not self.active(t_s) or t_s < self.next_request_s - 1e-9:
            return
        self.next_request_s = t_s + self.param("request_every_s", 2.0)
        if self.link is None:
            self.link = mavutil.mavlink_connection("udpout:127.0.0.1:%d" % self.ctx.gs_port, source_system=255,
                                                   source_component=190, input=False)
        before = self.forwarded
        result = "no answer"
        for _ in range(3):
            self.link.mav.command_long_send(1, 1, mavutil.mavlink.MAV_CMD_DO_SET_MODE, 0,
                                            mavutil.mavlink.MAV_MODE_FLAG_CUSTOM_MODE_ENABLED, 0, 0, 0, 0, 0, 0)
            deadline = time.monotonic() + 3.0
            ack = None
            while time.monotonic() < deadline:
                ack = self.link.recv_match(type="COMMAND_ACK", blocking=True, timeout=0.2)
                if ack is not None and ack.command == mavutil.mavlink.MAV_CMD_DO_SET_MODE:
                    break
                ack = None
            if ack is not None:
                result = mavutil.mavlink.enums["MAV_RESULT"][ack.result].name
                break
        deadline = time.monotonic() + 5.0
        while result == "MAV_RESULT_ACCEPTED" and self.forwarded == before and time.monotonic() < deadline:
            time.sleep(0.01)
        self.acks.append((t_s, result))
        self.note(t_s, "ground station asks for the HP: %s, %s" % (
            result, "forwarded" if self.forwarded > before else "not seen on /operator_command"))

    def effect(self):
        ok, why = super().effect()
        accepted = sum(1 for _, r in self.acks if r == "MAV_RESULT_ACCEPTED")
        return ok and accepted > 0 and self.forwarded > 0, "%s; %d requests for the HP, %d accepted, %d on /operator_command" % (
            why, len(self.acks), accepted, self.forwarded)


# What a campaign draws for this class (hil/campaigns/plan.py says how).
CAMPAIGN_PARAMS = {"surface": SURFACES}


def inject(ctx, at_s, duration_s, params):
    return GsRequestHp(ctx, at_s, duration_s, params)
