"""The simulator's end of the control channel to the HA in the loop (arduino_ha/src/hil/ha_sil_channel.h
states the records; the struct formats below are the same layouts, checked by
hil/test/test_ha_channel.py against a running ha_sil)."""
import os
import socket
import struct
from collections import namedtuple

MAGIC_STEP = 0x50545348
MAGIC_POLL = 0x4C505348
MAGIC_REPLY = 0x4C505248
MAGIC_RESET = 0x54535248
VERSION = 1

WAIT_COMMAND, AIRSPEED_OK, BATTERY_OK, RC_VALID, WAIT_COUNT = 1, 2, 4, 8, 16
R_LINK_CONNECTED, R_COMMAND_TIMEOUT, R_VN_TIMEOUT, R_STATE_VALID = 1, 2, 4, 8
R_HP_RESET, R_RESTART_REQUESTED, R_STEPPED, R_HOME = 16, 32, 64, 128

STEP = struct.Struct("<IHHQQII5HHff")
REPLY = struct.Struct("<IHHQ4f4fBBHIIIIfffIIIII")
assert STEP.size == 52 and REPLY.size == 100

Reply = namedtuple("Reply", "flags t_us applied ha_command controller leds restart_count reasons "
                            "reasons_at_switch last_seq commands_received stable_for_s "
                            "state_region_max actuator_region_max vn_bytes_read "
                            "ins_solutions_used ins_solutions_rejected ins_bad_packets wait_us")


def decode_reply(data):
    v = REPLY.unpack(data)
    if v[0] != MAGIC_REPLY or v[1] != VERSION:
        raise ValueError("not an HA reply record")
    return Reply(v[2], v[3], v[4:8], v[8:12], *v[12:])


class HaChannel:
    """Listens on a unix SOCK_SEQPACKET socket for ha_sil --lockstep PATH."""

    def __init__(self, path):
        self.path = path
        if os.path.exists(path):
            os.unlink(path)
        self.server = socket.socket(socket.AF_UNIX, socket.SOCK_SEQPACKET)
        self.server.bind(path)
        self.server.listen(1)
        self.conn = None

    def accept(self, timeout_s):
        self.server.settimeout(timeout_s)
        try:
            self.conn, _ = self.server.accept()
        except socket.timeout:
            return False
        self.conn.settimeout(None)
        return True

    def _exchange(self, record, timeout_s):
        self.conn.settimeout(timeout_s)
        self.conn.send(record)
        data = self.conn.recv(256)
        if not data:
            raise ConnectionError("ha_sil closed the control channel")
        return decode_reply(data)

    def poll(self, timeout_s=5.0):
        return self._exchange(STEP.pack(MAGIC_POLL, VERSION, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0.0, 0.0),
                              timeout_s)

    def reset(self, timeout_s=30.0):
        """Lockstep: resets the HA as a watchdog or brown-out reset does (RAM afresh, the board's
        retained words kept); answered with a reply, without a period of the core."""
        return self._exchange(self._reset_record(), timeout_s)

    def send_reset(self):
        """Real time: the same reset; the SIL's next period replies as usual."""
        self.conn.send(self._reset_record())

    @staticmethod
    def _reset_record():
        return STEP.pack(MAGIC_RESET, VERSION, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0.0, 0.0)

    def step(self, t_us, vn_bytes, cmd_seq, wait_ms, rc_pulses_us, rc_valid, airspeed_ftps,
             battery_v, airspeed_ok=True, battery_ok=True, timeout_s=30.0, wait_count=False):
        """One period. cmd_seq None: no HP command to wait for. wait_count: cmd_seq is the number
        of HP commands the link must have delivered since the start (a relay may repeat or
        replay sequence numbers), not a sequence number."""
        flags = (WAIT_COMMAND if cmd_seq is not None else 0) | (RC_VALID if rc_valid else 0) | \
            (WAIT_COUNT if wait_count and cmd_seq is not None else 0) | \
            (AIRSPEED_OK if airspeed_ok else 0) | (BATTERY_OK if battery_ok else 0)
        rec = STEP.pack(MAGIC_STEP, VERSION, flags, t_us, vn_bytes,
                        (cmd_seq or 0) & 0xFFFFFFFF, wait_ms, *rc_pulses_us, 0, airspeed_ftps, battery_v)
        return self._exchange(rec, timeout_s)

    def send_inputs(self, rc_pulses_us, rc_valid, airspeed_ftps, battery_v, airspeed_ok=True,
                    battery_ok=True):
        """Real time: the board inputs only (the SIL keeps its own clock and answers a reply
        after each of its periods, which latest_reply() collects)."""
        flags = (RC_VALID if rc_valid else 0) | (AIRSPEED_OK if airspeed_ok else 0) | \
            (BATTERY_OK if battery_ok else 0)
        self.conn.send(STEP.pack(MAGIC_STEP, VERSION, flags, 0, 0, 0, 0, *rc_pulses_us, 0,
                                 airspeed_ftps, battery_v))

    def pending_replies(self):
        """Real time: every reply waiting, oldest first."""
        out = []
        while True:
            try:
                data = self.conn.recv(256, socket.MSG_DONTWAIT)
            except BlockingIOError:
                return out
            if not data:
                raise ConnectionError("ha_sil closed the control channel")
            out.append(decode_reply(data))

    def latest_reply(self):
        """Real time: the newest reply waiting, or None."""
        replies = self.pending_replies()
        return replies[-1] if replies else None

    def close(self):
        for s in (self.conn, self.server):
            if s is not None:
                s.close()
        if os.path.exists(self.path):
            os.unlink(self.path)
