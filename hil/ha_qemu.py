#!/usr/bin/env python3
"""The HA as Cortex-M3 machine code in the loop (processor in the loop): QEMU's mps2-an385 running
the firmware image of arduino_ha/pil (make pil-image), in place of the host SIL (ha_sil).

    ha_qemu.py --port PATH --vn200 PATH --lockstep SOCKET [--rate-hz 100] [--image ELF]
               [--icount] [--record-log FILE]

takes ha_sil's arguments, so the launch file starts either. QEMU's UART0 is the HP link: its pty
is published under --port (a symlink, like /dev/ttyACM0) for the real `arduino` node. UART1 is the
VN-200's port 1: QEMU opens the simulator's pty (--vn200) itself. UART2 carries the simulator's
control records (arduino_ha/sil/ha_sil_channel.h) framed with a length and a CRC-32
(arduino_ha/pil/pil_frame.h); this process connects to the simulator's control socket as ha_sil
does and carries each record to the board and its reply back, without the reply's trailer (the
board's count of dropped records and the period's instruction ticks), which --record-log writes
one line a reply ("t_us dropped ticks"). Lockstep only: real time (--realtime) is not built.
--icount runs QEMU with -icount shift=0, so a timer tick is 40 instructions (bench/insn_timer.h).
SIGINT/SIGTERM, or the simulator closing the socket, stop QEMU and remove the symlink."""
import argparse
import os
import re
import select
import signal
import socket
import struct
import subprocess
import sys
import termios
import time
import tty
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
DEFAULT_IMAGE = os.path.join(ROOT, ".build", "pil", "ha_pil.elf")
SYNC = b"\xa5\x5a"
REPLY_LEN = 100
TRAILER = struct.Struct("<II")


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


def raw_open(path):
    fd = os.open(path, os.O_RDWR | os.O_NOCTTY | os.O_NONBLOCK)
    tty.setraw(fd)
    attrs = termios.tcgetattr(fd)
    attrs[3] &= ~termios.ECHO
    termios.tcsetattr(fd, termios.TCSANOW, attrs)
    return fd


class QemuBoard:
    """QEMU running the PIL image: start() boots it with the three UARTs wired, exchange() sends a
    record and returns (reply record, records dropped, period ticks), stop() ends QEMU."""

    def __init__(self, image=DEFAULT_IMAGE, vn200_path=None, icount=False):
        if not os.path.exists(image):
            raise FileNotFoundError("no PIL image at %s: run make pil-image" % image)
        self.image, self.vn200_path, self.icount = image, vn200_path, icount
        self.proc = None
        self.hp_pty = None
        self.hp_hold = self.ctl = None
        self.reader = FrameReader()

    def start(self, timeout_s=20.0):
        ins = ("serial,id=ins,path=%s" % os.path.realpath(self.vn200_path)) if self.vn200_path \
            else "null,id=ins"
        argv = ["qemu-system-arm", "-M", "mps2-an385", "-cpu", "cortex-m3", "-nographic",
                "-monitor", "none", "-kernel", self.image,
                "-chardev", "pty,id=hp", "-serial", "chardev:hp",
                "-chardev", ins, "-serial", "chardev:ins",
                "-chardev", "pty,id=ctl", "-serial", "chardev:ctl"]
        if self.icount:
            argv += ["-icount", "shift=0,align=off,sleep=off"]
        self.proc = subprocess.Popen(argv, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                                     stderr=subprocess.STDOUT)
        ptys, seen = {}, b""
        deadline = time.monotonic() + timeout_s
        while len(ptys) < 2:
            if time.monotonic() > deadline or self.proc.poll() is not None:
                self.stop()
                raise RuntimeError("qemu did not come up: %s" % seen.decode(errors="replace"))
            r, _, _ = select.select([self.proc.stdout], [], [], 0.2)
            if r:
                seen += os.read(self.proc.stdout.fileno(), 4096)
                for m in re.finditer(rb"redirected to (/dev/pts/\d+) \(label (\w+)\)", seen):
                    ptys[m.group(2).decode()] = m.group(1).decode()
        self.hp_pty = ptys["hp"]
        # Held open, as ha_sil holds its pty's slave: the node opening and closing its end never
        # makes QEMU see the line hang up.
        self.hp_hold = raw_open(self.hp_pty)
        self.ctl = raw_open(ptys["ctl"])
        return self

    def write_raw(self, data):
        """Bytes onto the control UART as they are (tests send damaged frames this way)."""
        view = memoryview(bytes(data))
        while view:
            try:
                n = os.write(self.ctl, view)
            except BlockingIOError:
                select.select([], [self.ctl], [], 1.0)
                continue
            view = view[n:]

    def read_reply(self, timeout_s):
        deadline = time.monotonic() + timeout_s
        while True:
            left = deadline - time.monotonic()
            if left <= 0:
                raise TimeoutError("the PIL board did not reply within %.1f s" % timeout_s)
            r, _, _ = select.select([self.ctl], [], [], left)
            if not r:
                continue
            try:
                data = os.read(self.ctl, 4096)
            except BlockingIOError:
                continue
            for payload in self.reader.feed(data):
                if len(payload) == REPLY_LEN + TRAILER.size:
                    dropped, ticks = TRAILER.unpack_from(payload, REPLY_LEN)
                    return payload[:REPLY_LEN], dropped, ticks

    def exchange(self, record, timeout_s=30.0):
        self.write_raw(frame(record))
        return self.read_reply(timeout_s)

    def stop(self):
        for fd in (self.hp_hold, self.ctl):
            if fd is not None:
                os.close(fd)
        self.hp_hold = self.ctl = None
        if self.proc is not None and self.proc.poll() is None:
            self.proc.terminate()
            try:
                self.proc.wait(timeout=10)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        if self.proc is not None and self.proc.stdout is not None:
            self.proc.stdout.close()


def publish(target, link):
    """link -> target, replaced atomically (the node may be polling for it)."""
    tmp = link + ".tmp"
    if os.path.lexists(tmp):
        os.unlink(tmp)
    os.symlink(target, tmp)
    os.rename(tmp, link)


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


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--port", required=True)
    ap.add_argument("--vn200", required=True)
    ap.add_argument("--lockstep", required=True)
    ap.add_argument("--rate-hz", type=float, default=100.0)
    ap.add_argument("--realtime", action="store_true")
    ap.add_argument("--image", default=DEFAULT_IMAGE)
    ap.add_argument("--icount", action="store_true")
    ap.add_argument("--record-log", default=None)
    args, _ = ap.parse_known_args(argv)  # roslaunch's __name:= and __log:=
    if args.realtime:
        print("ha_qemu: real time is not built: the PIL board runs in lockstep only", file=sys.stderr)
        return 2
    if abs(args.rate_hz - 100.0) > 1e-6:
        print("ha_qemu: the image runs the aircraft's period; --rate-hz %g is not it" % args.rate_hz,
              file=sys.stderr)
        return 2
    stop = {"now": False}

    def on_signal(_sig, _frame):
        stop["now"] = True
    signal.signal(signal.SIGINT, on_signal)
    signal.signal(signal.SIGTERM, on_signal)
    if not wait_for(args.vn200, stop):
        print("ha_qemu: no VN-200 port at %s" % args.vn200, file=sys.stderr)
        return 1
    chan = connect(args.lockstep, stop)
    if chan is None:
        print("ha_qemu: cannot connect to the simulator at %s" % args.lockstep, file=sys.stderr)
        return 1
    board = QemuBoard(args.image, args.vn200, args.icount).start()
    log = open(args.record_log, "w", buffering=1) if args.record_log else None
    replies = 0
    try:
        publish(board.hp_pty, args.port)
        print("ha_qemu: up on %s (%s), lockstep with %s" % (args.port, board.hp_pty, args.lockstep),
              file=sys.stderr)
        while not stop["now"]:
            r, _, _ = select.select([chan], [], [], 0.2)
            if not r:
                if board.proc.poll() is not None:
                    print("ha_qemu: qemu ended (%s)" % board.proc.returncode, file=sys.stderr)
                    return 1
                continue
            record = chan.recv(256)
            if not record:
                print("ha_qemu: simulator closed the control channel", file=sys.stderr)
                break
            reply, dropped, ticks = board.exchange(record, timeout_s=120.0)
            replies += 1
            if log:
                log.write("%d %d %d\n" % (struct.unpack_from("<Q", reply, 8)[0], dropped, ticks))
            chan.send(reply)
    except (TimeoutError, OSError) as e:
        print("ha_qemu: %s" % e, file=sys.stderr)
        return 1
    finally:
        board.stop()
        if os.path.lexists(args.port):
            os.unlink(args.port)
        chan.close()
        if log:
            log.close()
        print("ha_qemu: %d replies, %d dropped reply frames" % (replies, board.reader.bad),
              file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
