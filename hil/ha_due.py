#!/usr/bin/env python3
"""The simulator's end of a real Due in the loop (run_flight.py --ha due --realtime): the Due runs
its HIL build (make due-hil-image; arduino_ha/README.md, "The Due in the loop"), which takes its
board inputs (RC, the AMS5812's airspeed, the battery) as the simulator's records on its native
USB port and answers each of its own periods with a reply (servos, the HP reset line, the
decision). This process carries them between that port and the simulator's control socket, as
ha_sil's own channel would, and copies the simulator's VN-200 port 1 (a pty) to the USB-serial
adapter wired to the Due's RX1, as the sensor's port 1 feeds Serial1 in flight. The HP link is
not here: the `arduino` node opens the Due's programming port itself.

    ha_due.py --native /dev/ttyACM1 --ins /dev/ttyUSB0 --vn200 PATH --lockstep SOCKET --realtime
              [--record-log FILE]

The records travel framed as the QEMU board's UART2 takes them (ha_qemu.frame: A5 5A, length,
record, CRC-32); a reply frame that fails its CRC is counted and dropped here. Real time only: the
Due keeps its own clock. The simulator dates each reply's period on its own clock (ha_sil's
micros() is the host's CLOCK_MONOTONIC), so each tick of the Due is put on that clock before the
reply goes on (DueClock). --record-log writes a line a reply ("due_us host_us dropped ticks
tx_dropped ins_dropped"): the period on the Due's clock and on the host's, the records the Due
dropped, how long its loop pass took (us), the reply bytes its port could not send, and the
VN-200 bytes the adapter here could not take. SIGINT/SIGTERM, or the simulator closing the
socket, end it."""
import argparse
import os
import select
import signal
import struct
import sys
import termios
import time
import tty

from hil import ha_qemu

T_US_AT = 8  # the reply's period time (ha_channel.REPLY: magic, version, flags, then t_us)
BAUD = termios.B115200  # the VN-200 port 1's rate; never 1200 on the native port (it erases the flash)


class DueClock:
    """The Due's period ticks (its micros(), 32 bits) on the host's clock (microseconds of
    time.monotonic(), 32 bits, as ha_sil stamps its own). A reply arrives some latency after its
    tick, never before, so arrival minus tick is the clocks' offset plus a latency >= 0: the
    least such difference seen is the offset plus the least latency (USB and this loop, well
    under a period). The Due's crystal drifts against the host's (tens of ppm, milliseconds over a
    flight), so the estimate may rise by DRIFT_PPM of the time since the last tick, while a
    smaller difference is taken at once: a lower envelope that follows drift and ignores late
    arrivals. The first ticks are dated with that first latency, at most."""

    DRIFT_PPM = 200.0

    def __init__(self):
        self.offset_us = None
        self.last_due_us = None

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
        return int(round(due_us + self.offset_us)) & 0xFFFFFFFF


def open_serial(path, flags):
    """A serial device (or a pty standing in for one) raw at 115200 baud, non-blocking, with what
    an earlier session left in its input dropped: a stale reply must not pass for a new one."""
    fd = os.open(path, flags | os.O_NOCTTY | os.O_NONBLOCK)
    tty.setraw(fd)
    attrs = termios.tcgetattr(fd)
    attrs[4] = attrs[5] = BAUD
    termios.tcsetattr(fd, termios.TCSANOW, attrs)
    termios.tcflush(fd, termios.TCIFLUSH)
    return fd


def wait_for_paths(paths, stop, timeout_s):
    deadline = time.monotonic() + timeout_s
    for path in paths:
        if not ha_qemu.wait_for(path, stop, max(0.0, deadline - time.monotonic())):
            return path
    return None


class DueBridge:
    """The native port's frames both ways and the VN-200's bytes one way; run() until stopped."""

    def __init__(self, chan, native_fd, ins_fd, vn_fd, log=None):
        self.chan, self.native, self.ins, self.vn = chan, native_fd, ins_fd, vn_fd
        self.log = log
        self.reader = ha_qemu.FrameReader()
        self.clock = DueClock()
        self.records = self.replies = 0
        self.records_unsent = 0  # record bytes the native port could not take
        self.ins_dropped = 0  # VN-200 bytes the adapter could not take

    def _write(self, fd, data):
        try:
            return os.write(fd, data)
        except BlockingIOError:
            return 0

    def run(self, stop):
        while not stop["now"]:
            r, _, _ = select.select([self.chan, self.native, self.vn], [], [], 0.2)
            if self.chan in r:
                record = self.chan.recv(256)
                if not record:
                    print("ha_due: simulator closed the control channel", file=sys.stderr)
                    return 0
                framed = ha_qemu.frame(record)
                self.records_unsent += len(framed) - self._write(self.native, framed)
                self.records += 1
            if self.native in r:
                data = os.read(self.native, 4096)
                arrival_us = int(time.monotonic() * 1e6)
                for payload in self.reader.feed(data):
                    self._reply(payload, arrival_us)
            if self.vn in r:
                try:
                    data = os.read(self.vn, 4096)
                except BlockingIOError:
                    data = b""
                if data:
                    self.ins_dropped += len(data) - self._write(self.ins, data)
        return 0

    def _reply(self, payload, arrival_us):
        if len(payload) != ha_qemu.REPLY_LEN + ha_qemu.TRAILER.size:
            self.reader.bad += 1
            return
        dropped, ticks, tx_dropped, _rx = ha_qemu.TRAILER.unpack_from(payload, ha_qemu.REPLY_LEN)
        reply = bytearray(payload[:ha_qemu.REPLY_LEN])
        due_us = struct.unpack_from("<Q", reply, T_US_AT)[0] & 0xFFFFFFFF
        host_us = self.clock.to_host(due_us, arrival_us & 0xFFFFFFFF)
        struct.pack_into("<Q", reply, T_US_AT, host_us)
        self.chan.send(bytes(reply))
        self.replies += 1
        if self.log:
            self.log.write("%d %d %d %d %d %d\n" % (due_us, host_us, dropped, ticks, tx_dropped, self.ins_dropped))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--native", required=True, help="the Due's native USB port (e.g. /dev/ttyACM1)")
    ap.add_argument("--ins", required=True, help="the USB-serial adapter wired to the Due's RX1 (e.g. /dev/ttyUSB0)")
    ap.add_argument("--vn200", required=True, help="the simulator's VN-200 port 1 (a pty)")
    ap.add_argument("--lockstep", required=True, help="the simulator's control socket")
    ap.add_argument("--realtime", action="store_true")
    ap.add_argument("--rate-hz", type=float, default=100.0)
    ap.add_argument("--record-log", default=None)
    args, _ = ap.parse_known_args(argv)  # roslaunch's __name:= and __log:=
    if not args.realtime:
        print("ha_due: a Due keeps its own clock: it flies in real time only (--realtime)", file=sys.stderr)
        return 2
    if abs(args.rate_hz - 100.0) > 1e-6:
        print("ha_due: the image runs the aircraft's period; --rate-hz %g is not it" % args.rate_hz,
              file=sys.stderr)
        return 2
    stop = {"now": False}

    def on_signal(_sig, _frame):
        stop["now"] = True
    signal.signal(signal.SIGINT, on_signal)
    signal.signal(signal.SIGTERM, on_signal)
    missing = wait_for_paths([args.native, args.ins, args.vn200], stop, 30.0)
    if missing is not None:
        print("ha_due: no device at %s" % missing, file=sys.stderr)
        return 1
    try:
        native = open_serial(args.native, os.O_RDWR)
        ins = open_serial(args.ins, os.O_WRONLY)
        vn = open_serial(args.vn200, os.O_RDONLY)
    except OSError as e:
        print("ha_due: %s" % e, file=sys.stderr)
        return 1
    chan = ha_qemu.connect(args.lockstep, stop)
    if chan is None:
        print("ha_due: cannot connect to the simulator at %s" % args.lockstep, file=sys.stderr)
        return 1
    log = open(args.record_log, "w", buffering=1) if args.record_log else None
    bridge = DueBridge(chan, native, ins, vn, log)
    print("ha_due: the Due's native port %s, RX1 through %s, real time with %s" %
          (args.native, args.ins, args.lockstep), file=sys.stderr)
    code = 1
    try:
        code = bridge.run(stop)
    except OSError as e:
        print("ha_due: %s (was the Due unplugged?)" % e, file=sys.stderr)
    finally:
        chan.close()
        for fd in (native, ins, vn):
            os.close(fd)
        if log:
            log.close()
        print("ha_due: %d records, %d replies, %d reply frames dropped here, %d record bytes the native port "
              "did not take, %d VN-200 bytes the adapter did not take" %
              (bridge.records, bridge.replies, bridge.reader.bad, bridge.records_unsent, bridge.ins_dropped),
              file=sys.stderr)
    return code


if __name__ == "__main__":
    sys.exit(main())
