"""Bit flips on the HP-HA link, in the bytes on the pty between the `arduino` node and the HA
(hil/link_relay.py, a man in the middle): one bit of each HP command frame of the window
(params target = payload (default: the 38 bytes the CRC covers) or crc (its 4 bytes); every_n,
default 1: every n-th command), chosen by a generator seeded with the flight's seed. The frame's
own rosserial checksum is made to match again, as two flips that cancel in its 8-bit sum would:
the corruption reaches the HA's CRC-32 check, the one meant to catch it. Took effect when a
corrupted frame was the last command the HA received in its period; a takeover is due then."""
import random
import struct
import threading

from hil import link_relay
from hil.faults.base import Fault

SERVO_COMMAND_BYTES = 42  # msg/ServoCommand.msg: 38 bytes of fields, then crc32


class LinkBitflip(Fault):
    NEEDS_RELAY = True      # commands pass through the simulator, so the HA waits by count
    NEEDS_LINK_RELAY = True

    def __init__(self, *a):
        super().__init__(*a)
        self.target = self.param("target", "payload")
        if self.target not in ("payload", "crc"):
            raise ValueError("link_bitflip: target must be payload or crc")
        self.every = max(1, int(self.param("every_n", 1.0)))
        self.rng = random.Random("%s/link_bitflip" % self.ctx.seed)
        self.lock = threading.Lock()
        self.window = False
        self.count = 0
        self.flipped = []    # (seq as sent, seq after the flip, byte, bit)
        self.expect = None   # (t_s, flipped seq) of this period
        self.received = []
        self.ctx.link_relay.hook = self.on_frame

    def on_frame(self, frame):
        topic, payload = link_relay.frame_topic_payload(frame)
        if topic < 100 or len(payload) != SERVO_COMMAND_BYTES:
            return frame
        with self.lock:
            if not self.window:
                return frame
            self.count += 1
            if (self.count - 1) % self.every:
                return frame
            lo, hi = (0, 38) if self.target == "payload" else (38, 42)
            byte = self.rng.randrange(lo, hi)
            bit = self.rng.randrange(8)
            p = bytearray(payload)
            p[byte] ^= 1 << bit
            seq_sent = struct.unpack_from("<I", payload)[0]
            seq_now = struct.unpack_from("<I", p)[0]
            self.flipped.append((seq_sent, seq_now, byte, bit))
            self.last = seq_now
        return link_relay.make_frame(topic, bytes(p))

    def command(self, t_s, msg):
        with self.lock:
            self.window = self.active(t_s)
            n = len(self.flipped)
        if msg is not None and self.window:
            self.expect = (t_s, n)
        return [] if msg is None else [msg]

    def after_step(self, t_s, reply):
        if self.expect is None or self.expect[0] != t_s:
            return
        with self.lock:
            new = self.flipped[self.expect[1]:]
        self.expect = None
        # The link handed the HA every frame relayed so far, the flipped one last (the HA's own
        # last_seq is that of its last intact command, so it cannot name a corrupted one).
        if new and reply.commands_received >= self.ctx.relayed:
            self.received.append((t_s, new[-1]))
            if len(self.received) == 1:
                self.due_s = t_s
                s, s2, byte, bit = new[-1]
                self.note(t_s, "seq %d: bit %d of byte %d flipped (%s); the HA received it: controller %d, reasons %#x" % (
                    s, bit, byte, self.target, reply.controller, reply.reasons))

    def effect(self):
        if not self.received:
            return False, "%d frames flipped, none reached the HA as its period's command" % len(self.flipped)
        return True, "%d frames flipped on the link, %d reached the HA as their period's command; %s" % (
            len(self.flipped), len(self.received), "; ".join(self.notes))


# What a campaign draws for this class (hil/campaigns/plan.py says how).
CAMPAIGN_PARAMS = {"target": ("payload", "crc"), "every_n": (1, 1, 3, 10)}


def inject(ctx, at_s, duration_s, params):
    return LinkBitflip(ctx, at_s, duration_s, params)
