"""The control records between the simulator and an HA board that keeps its own clock (a real
Due, ha_due.py; QEMU in real time, ha_qemu.py --realtime): their framing on a byte stream (what
the QEMU board's UART2 and the Due's native USB port take: A5 5A, length, record, CRC-32), the
board's ticks put on the host's clock (HaClock), and the bridge that carries them (RecordBridge).
The simulator's side is its control socket (ha_channel), which ha_sil --realtime serves itself."""
import os
import select
import signal
import socket
import struct
import sys
import time
import zlib

from hil.aircraft_period import decision_rate_hz

SYNC = b"\xa5\x5a"
REPLY_LEN = 100
TRAILER = struct.Struct("<IIII")


def frame(payload):
    """A control record as the board's UART2 takes it (pil_frame.h)."""
    head = struct.pack("<H", len(payload))
    return SYNC + head + bytes(payload) + struct.pack("<I", zlib.crc32(head + bytes(payload)))


class FrameReader:
    """Whole, checked frames out of the board's byte stream (the board sends nothing else)."""

    def __init__(self):
        self.buf = bytearray()
        self.bad = 0

    def feed(self, data):
        self.buf += data
        out = []
        while True:
            start = self.buf.find(SYNC)
            if start < 0:
                del self.buf[:-1]
                return out
            del self.buf[:start]
            if len(self.buf) < 4:
                return out
            n = self.buf[2] | self.buf[3] << 8
            if len(self.buf) < n + 8:
                return out
            body = bytes(self.buf[2:4 + n])
            if struct.unpack_from("<I", self.buf, 4 + n)[0] == zlib.crc32(body):
                out.append(body[2:])
                del self.buf[:n + 8]
            else:
                self.bad += 1
                del self.buf[:1]


T_US_AT = 8  # the reply's period time (ha_channel.REPLY: magic, version, flags, then t_us)


class HaClock:
    """A board's period ticks (its micros(), 32 bits) on the host's clock (microseconds of
    time.monotonic(), 32 bits, as ha_sil stamps its own). A reply arrives some latency after its
    tick, never before, so arrival minus tick is the clocks' offset plus a latency >= 0: the
    least such difference seen is the offset plus the least latency (USB and this loop, well
    under a period). A Due's crystal drifts against the host's (tens of ppm, milliseconds over a
    flight), so the estimate may rise by DRIFT_PPM of the time since the last tick, while a
    smaller difference is taken at once: a lower envelope that follows drift and ignores late
    arrivals. The first ticks are dated with that first latency, at most. A tick is never dated at
    or before the one it follows: when the replies came late for a while (this process starved of
    the CPU) and then one comes on time, the envelope drops at once, and the late ones, already
    passed on, were dated too late; the new one then goes 1 us after the last (the simulator
    needs its periods in order)."""

    DRIFT_PPM = 200.0

    def __init__(self):
        self.offset_us = None
        self.last_due_us = None
        self.last_host_us = None

    def to_host(self, due_us, arrival_us):
        """The host time (us, 32 bits) of the Due's tick due_us, which arrived at arrival_us."""
        sample = (arrival_us - due_us) & 0xFFFFFFFF
        if self.offset_us is None:
            self.offset_us = float(sample)
        else:
            allowed = ((due_us - self.last_due_us) & 0xFFFFFFFF) * self.DRIFT_PPM * 1e-6
            below = ((sample - self.offset_us + 2 ** 31) % 2 ** 32) - 2 ** 31  # signed: both clocks wrap
            self.offset_us = (self.offset_us + min(allowed, below)) % 2 ** 32
        self.last_due_us = due_us
        host_us = int(round(due_us + self.offset_us)) & 0xFFFFFFFF
        if self.last_host_us is not None and not 0 < ((host_us - self.last_host_us) & 0xFFFFFFFF) < 2 ** 31:
            host_us = (self.last_host_us + 1) & 0xFFFFFFFF
        self.last_host_us = host_us
        return host_us


class RecordBridge:
    """The records framed onto the board's stream (board_fd, non-blocking: the Due's native port,
    QEMU's control UART) and its replies back to the simulator's socket (chan), each reply's
    period put on the host's clock; with vn_fd and ins_fd, the VN-200's bytes copied from the
    simulator's pty to the board's INS port as well. run() until stopped or the simulator closes. With log, a
    line a reply: "board_us host_us dropped ticks tx_dropped rx_dropped ins_dropped" (the period
    on the board's clock and on the host's; the trailer's records dropped, loop pass ticks, bytes
    the board could not send, bytes to its full receive ring; VN-200 bytes not passed on here)."""

    def __init__(self, chan, board_fd, ins_fd=None, vn_fd=None, log=None):
        self.chan, self.native, self.ins, self.vn = chan, board_fd, ins_fd, vn_fd
        self.log = log
        self.reader = FrameReader()
        self.clock = HaClock()
        self.records = self.replies = 0
        self.records_unsent = 0  # record bytes the native port could not take
        self.ins_dropped = 0  # VN-200 bytes the adapter could not take
        # The board's own counts as of its latest reply: bytes its UARTs could not send, and bytes
        # that came to a full receive ring (what ha_qemu's and ha_due's closing lines report).
        self.tx_dropped = self.rx_dropped = 0
        # What the board sent before this bridge was made would be dated at its late arrival:
        # gone, here and not in run(), so that nothing sent once the bridge exists is dropped
        # however late its thread first runs.
        try:
            while os.read(self.native, 4096):
                pass
        except BlockingIOError:
            pass

    def _write(self, fd, data):
        try:
            return os.write(fd, data)
        except BlockingIOError:
            return 0

    def run(self, stop):
        while not stop["now"]:
            r, _, _ = select.select([f for f in (self.chan, self.native, self.vn) if f is not None], [], [], 0.2)
            if self.chan in r:
                try:
                    record = self.chan.recv(256)
                except ConnectionResetError:
                    record = b""
                if not record:
                    print("record_bridge: simulator closed the control channel", file=sys.stderr)
                    return 0
                framed = frame(record)
                self.records_unsent += len(framed) - self._write(self.native, framed)
                self.records += 1
            if self.native in r:
                data = os.read(self.native, 4096)
                if not data:
                    print("record_bridge: the board closed its port", file=sys.stderr)
                    return 1
                arrival_us = int(time.monotonic() * 1e6)
                for payload in self.reader.feed(data):
                    self._reply(payload, arrival_us)
            if self.vn is not None and self.vn in r:
                try:
                    data = os.read(self.vn, 4096)
                except BlockingIOError:
                    data = b""
                if data:
                    self.ins_dropped += len(data) - self._write(self.ins, data)
        return 0

    def _reply(self, payload, arrival_us):
        if len(payload) != REPLY_LEN + TRAILER.size:
            self.reader.bad += 1
            return
        dropped, ticks, tx_dropped, rx_dropped = TRAILER.unpack_from(payload, REPLY_LEN)
        self.tx_dropped, self.rx_dropped = tx_dropped, rx_dropped
        reply = bytearray(payload[:REPLY_LEN])
        due_us = struct.unpack_from("<Q", reply, T_US_AT)[0] & 0xFFFFFFFF
        host_us = self.clock.to_host(due_us, arrival_us & 0xFFFFFFFF)
        struct.pack_into("<Q", reply, T_US_AT, host_us)
        self.chan.send(bytes(reply))
        self.replies += 1
        if self.log:
            self.log.write("%d %d %d %d %d %d %d\n" % (due_us, host_us, dropped, ticks, tx_dropped, rx_dropped,
                                                       self.ins_dropped))


def board_period_refused(name, rate_hz, aircraft_dir):
    """The board's image runs its aircraft's period (limits.yaml's decision.rate_hz, from which
    the image's configuration is generated): for another rate, says so on stderr and returns the
    exit code 2; None for the period itself."""
    period_hz = decision_rate_hz(aircraft_dir)
    if rate_hz is not None and abs(rate_hz - period_hz) > 1e-6:
        print("%s: the image runs the aircraft's period (%g Hz in %s); --rate-hz %g is not it" %
              (name, period_hz, aircraft_dir, rate_hz), file=sys.stderr)
        return 2
    return None


def stop_on_signals():
    """A flag, {"now": bool}, that SIGINT and SIGTERM (roslaunch's stop) set: the loops that
    wait for the board or carry its records end at the next look."""
    stop = {"now": False}

    def on_signal(_sig, _frame):
        stop["now"] = True
    signal.signal(signal.SIGINT, on_signal)
    signal.signal(signal.SIGTERM, on_signal)
    return stop


def wait_for(path, stop, timeout_s=30.0):
    deadline = time.monotonic() + timeout_s
    while not os.path.exists(path):
        if stop["now"] or time.monotonic() > deadline:
            return False
        time.sleep(0.1)
    return True


def connect(path, stop, timeout_s=30.0):
    deadline = time.monotonic() + timeout_s
    while not stop["now"] and time.monotonic() < deadline:
        s = socket.socket(socket.AF_UNIX, socket.SOCK_SEQPACKET)
        try:
            s.connect(path)
            return s
        except OSError:
            s.close()
            time.sleep(0.1)
    return None


