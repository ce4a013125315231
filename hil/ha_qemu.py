#!/usr/bin/env python3
"""The HA as Cortex-M3 machine code in the loop (processor in the loop): QEMU's mps2-an385 running
the firmware image of arduino_ha/pil (make pil-image), in place of the host SIL (ha_sil).

    ha_qemu.py --port PATH --vn200 PATH --lockstep SOCKET --aircraft-dir aircraft/DG808
               [--rate-hz 100] [--image ELF] [--icount] [--record-log FILE]

takes ha_sil's arguments and the aircraft whose period the image runs, so the launch file starts
either. QEMU's UART0 is the HP link: a pty this process serves for it (QemuBoard says why not
QEMU's own) is published under --port (a symlink, like /dev/ttyACM0) for the real `arduino` node. UART1 is the VN-200's port 1: QEMU opens
the simulator's pty (--vn200) itself. UART2 carries the simulator's control records (arduino_ha/src/hil/ha_sil_channel.h) framed with a length and a CRC-32
(arduino_ha/src/hil/pil_frame.h); this process connects to the simulator's control socket as ha_sil
does and carries each record to the board and its reply back, without the reply's trailer (the
board's count of dropped records, the period's instruction ticks and the bytes its UARTs
dropped, the bytes that came to a full receive ring), which --record-log writes one line a reply
("t_us dropped ticks tx_dropped host_dropped rx_dropped").

--realtime flies an image built with PIL_CFLAGS=-DPIL_REALTIME=1 (run_flight.py --ha qemu
--realtime builds it into the flight's folder; the default image is the lockstep one and is
refused): the board keeps its own clock (QEMU's virtual clock, which follows the host's), a step
record only brings its inputs, and each period it ran comes back as a reply, as a real Due's HIL
build does; record_bridge.RecordBridge carries the records and replies and puts the board's
ticks on the host's clock, and --record-log then writes its line a reply.
--icount runs QEMU with -icount shift=0, so a timer tick is 40 instructions (bench/insn_timer.h).
SIGINT/SIGTERM, or the simulator closing the socket, stop QEMU and remove the symlink."""
import argparse
import os
import select
import shutil
import socket
import struct
import subprocess
import sys
import tempfile
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
from hil import ptys, record_bridge  # noqa: E402
from hil.record_bridge import REPLY_LEN, TRAILER, FrameReader, connect, frame, wait_for  # noqa: E402
DEFAULT_IMAGE = os.path.join(ROOT, ".build", "pil", "ha_pil.elf")


class QemuBoard:
    """QEMU running the PIL image: start() boots it with the three UARTs wired, exchange() sends a
    record and returns (reply record, records dropped, period ticks), stop() ends QEMU.

    QEMU's own pty backend marks its pty hung up on a read that finds nothing and then drops what
    the guest writes until a 1 s timer finds it up again (a /pwm lost that way stalled a flight), so
    the HP link and the control UART are QEMU unix-socket chardevs: the control socket is talked to
    directly, and the HP link's bytes are carried by a thread between that socket and a pty this
    class owns (hp_pty), the way ha_sil serves its own pty. The VN-200 is QEMU's serial backend on
    the simulator's pty, which it opens as any program opens a serial port."""

    def __init__(self, image=DEFAULT_IMAGE, vn200_path=None, icount=False):
        if not os.path.exists(image):
            raise FileNotFoundError("no PIL image at %s: run make pil-image" % image)
        self.image, self.vn200_path, self.icount = image, vn200_path, icount
        self.proc = None
        self.dir = None
        self.hp_pty = None
        self.hp_master = self.hp_slave = self.hp_sock = self.ctl = None
        self.relay = None
        self.stopping = threading.Event()
        self.reader = FrameReader()
        self.tx_dropped = 0  # bytes the board's UARTs could not send (its latest reply's count)
        self.rx_dropped = 0  # bytes that came to a full receive ring of the board (the same)
        self.hp_link_dropped = 0  # bytes for the host its pty could not take
        self.to_host = self.to_board = 0  # bytes the HP link's relay carried each way
        self.relay_end = None  # why the relay stopped before stop() asked it to

    def start(self, timeout_s=20.0):
        self.dir = tempfile.mkdtemp(prefix="ha_qemu_")
        ins = ("serial,id=ins,path=%s" % os.path.realpath(self.vn200_path)) if self.vn200_path \
            else "null,id=ins"
        socks = {name: os.path.join(self.dir, name) for name in ("hp", "ctl")}
        argv = ["qemu-system-arm", "-M", "mps2-an385", "-cpu", "cortex-m3", "-nographic",
                "-monitor", "none", "-kernel", self.image,
                "-chardev", "socket,id=hp,path=%s,server=on,wait=off" % socks["hp"], "-serial", "chardev:hp",
                "-chardev", ins, "-serial", "chardev:ins",
                "-chardev", "socket,id=ctl,path=%s,server=on,wait=off" % socks["ctl"], "-serial", "chardev:ctl"]
        if self.icount:
            # sleep=on: while the guest sleeps in WFI waiting for bytes, its clock follows the
            # host's; sleep=off would jump it to the wait's deadline before the bytes could come.
            argv += ["-icount", "shift=0,align=off,sleep=on"]
        self.proc = subprocess.Popen(argv, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                     stderr=subprocess.PIPE)
        deadline = time.monotonic() + timeout_s
        conns = {}
        while len(conns) < 2:
            if time.monotonic() > deadline or self.proc.poll() is not None:
                err = self.proc.stderr.read().decode(errors="replace") if self.proc.poll() is not None else ""
                self.stop()
                raise RuntimeError("qemu did not come up: %s" % err)
            for name, path in socks.items():
                if name in conns or not os.path.exists(path):
                    continue
                s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
                try:
                    s.connect(path)
                    conns[name] = s
                except OSError:
                    s.close()
            time.sleep(0.05)
        self.hp_sock, self.ctl = conns["hp"], conns["ctl"]
        self.hp_master, self.hp_slave = ptys.open_raw()
        self.hp_pty = os.ttyname(self.hp_slave)  # the slave stays open: the node's reopen never hangs up
        self.relay = threading.Thread(target=self._carry_hp_link, daemon=True)
        self.relay.start()
        return self

    def _carry_hp_link(self):
        """The HP link's bytes both ways; what the host's side cannot take now is dropped, as a
        full USB buffer drops it (the link is built to lose bytes). The board's bytes go on to the
        host a whole rosserial frame at a time (whole_frames). A relay that stops before stop()
        says why on stderr at once: the link is dead from then on (CI, once: the arduino node's
        topic requests never answered for 120 s, and nothing told which side had gone)."""
        held = bytearray()
        try:
            while not self.stopping.is_set():
                r, _, _ = select.select([self.hp_master, self.hp_sock], [], [], 0.2)
                try:
                    if self.hp_sock in r:
                        data = self.hp_sock.recv(65536)
                        if not data:
                            self.relay_end = "QEMU closed the HP link's socket"
                            break
                        held += data
                        out = whole_frames(held)
                        try:
                            written = os.write(self.hp_master, out) if out else 0
                        except BlockingIOError:
                            written = 0
                        self.to_host += written
                        self.hp_link_dropped += len(out) - written
                    if self.hp_master in r:
                        data = os.read(self.hp_master, 65536)
                        self.hp_sock.sendall(data)
                        self.to_board += len(data)
                except (BlockingIOError, InterruptedError):
                    continue
        except Exception as e:  # noqa: BLE001  any end of the relay is the HP link's end: say which
            self.relay_end = "%s: %s" % (type(e).__name__, e)
        if self.relay_end is not None and not self.stopping.is_set():
            print("ha_qemu: the HP link's relay stopped: %s (%d bytes to the host, %d to the board)" %
                  (self.relay_end, self.to_host, self.to_board), file=sys.stderr, flush=True)

    def write_raw(self, data):
        """Bytes onto the control UART as they are (tests send damaged frames this way)."""
        self.ctl.sendall(bytes(data))

    def read_reply(self, timeout_s):
        self.ctl.settimeout(timeout_s)
        deadline = time.monotonic() + timeout_s
        while True:
            if time.monotonic() > deadline:
                raise TimeoutError("the PIL board did not reply within %.1f s" % timeout_s)
            try:
                data = self.ctl.recv(4096)
            except socket.timeout:
                continue
            if not data:
                raise ConnectionError("qemu closed the control UART")
            for payload in self.reader.feed(data):
                if len(payload) == REPLY_LEN + TRAILER.size:
                    dropped, ticks, self.tx_dropped, self.rx_dropped = TRAILER.unpack_from(payload, REPLY_LEN)
                    return payload[:REPLY_LEN], dropped, ticks

    def exchange(self, record, timeout_s=30.0):
        self.write_raw(frame(record))
        return self.read_reply(timeout_s)

    def stop(self):
        self.stopping.set()
        if self.proc is not None and self.proc.poll() is None:
            self.proc.terminate()
            try:
                self.proc.wait(timeout=10)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        if self.proc is not None and self.proc.stderr is not None:
            self.proc.stderr.close()
        if self.relay is not None:
            self.relay.join(timeout=5)
        for s in (self.hp_sock, self.ctl):
            if s is not None:
                s.close()
        for fd in (self.hp_master, self.hp_slave):
            if fd is not None:
                os.close(fd)
        self.hp_sock = self.ctl = self.hp_master = self.hp_slave = None
        if self.dir is not None:
            shutil.rmtree(self.dir, ignore_errors=True)


def whole_frames(held):
    """Cuts off the front of held what can go to the host now: bytes before a rosserial frame's
    start, and whole frames (v2 header: FF FE, length, length checksum; then topic, payload,
    checksum). A started frame waits for its last byte. Why: the guest writes its UART a byte at
    a time, and a QEMU descheduled on a loaded host mid-frame split a frame by more than the
    arduino node's 50 ms frame timeout, which dropped it (a lost /decision_status stalled a
    lockstep flight); the Due's USB sends a frame in a few 64-byte packets within a millisecond.
    Bytes are never changed, dropped or reordered here."""
    out = bytearray()
    while held:
        start = held.find(b"\xff\xfe")
        if start != 0:
            cut = len(held) if start < 0 else start
            if start < 0 and held[-1] == 0xFF:
                cut -= 1  # may be the start of a frame's header
            out += held[:cut]
            del held[:cut]
            if start < 0:
                break
            continue
        if len(held) < 5:
            break
        n = held[2] | held[3] << 8
        if (held[2] + held[3] + held[4]) % 256 != 255 or n > 1024:
            out += held[:1]  # no frame header after all: on to the next FF FE
            del held[:1]
            continue
        if len(held) < n + 8:
            break
        out += held[:n + 8]
        del held[:n + 8]
    return bytes(out)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--port", required=True)
    ap.add_argument("--vn200", required=True)
    ap.add_argument("--lockstep", required=True)
    ap.add_argument("--rate-hz", type=float, default=None, help="the aircraft's (the only one the image runs)")
    ap.add_argument("--aircraft-dir", required=True, help="the aircraft folder the image was built from")
    ap.add_argument("--realtime", action="store_true")
    ap.add_argument("--image", default=DEFAULT_IMAGE, help="the PIL image ('default': %s)" % DEFAULT_IMAGE)
    ap.add_argument("--icount", action="store_true")
    ap.add_argument("--record-log", default=None)
    args, _ = ap.parse_known_args(argv)  # roslaunch's __name:= and __log:=
    if args.image == "default":  # what the launch file passes without ha_image
        args.image = DEFAULT_IMAGE
    if args.realtime and os.path.realpath(args.image) == os.path.realpath(DEFAULT_IMAGE):
        print("ha_qemu: --realtime needs the real-time image (build_pil_image.sh with "
              "PIL_CFLAGS=-DPIL_REALTIME=1, as run_flight.py --ha qemu --realtime does), not %s" % args.image,
              file=sys.stderr)
        return 2
    refused = record_bridge.board_period_refused("ha_qemu", args.rate_hz, args.aircraft_dir)
    if refused is not None:
        return refused
    stop = record_bridge.stop_on_signals()
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
        ptys.publish(board.hp_pty, args.port)
        print("ha_qemu: up on %s (%s), %s with %s" % (args.port, board.hp_pty,
                                                      "real time" if args.realtime else "lockstep", args.lockstep),
              file=sys.stderr)
        if args.realtime:
            board.ctl.setblocking(False)  # before the bridge drains what the board sent so far
            bridge = record_bridge.RecordBridge(chan, board.ctl.fileno(), log=log)
            code = bridge.run(stop)
            replies, board.reader = bridge.replies, bridge.reader
            # The closing line's counts: in real time the replies carry them to the bridge (CI's
            # failed flight's line said 0 bytes dropped; its replies said 848).
            board.tx_dropped, board.rx_dropped = bridge.tx_dropped, bridge.rx_dropped
            return code
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
                log.write("%d %d %d %d %d %d\n" % (struct.unpack_from("<Q", reply, 8)[0], dropped, ticks,
                                                 board.tx_dropped, board.hp_link_dropped, board.rx_dropped))
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
        print("ha_qemu: %d replies, %d reply frames dropped here, %d bytes dropped by the board's UARTs, "
              "%d bytes for the host its pty could not take; HP link %d bytes to the host, %d to the board" % (
                  replies, board.reader.bad, board.tx_dropped, board.hp_link_dropped, board.to_host,
                  board.to_board), file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
