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
              --aircraft-dir aircraft/DG808 [--record-log FILE]

--aircraft-dir names the aircraft the Due's image was built for: its period (limits.yaml's
decision.rate_hz) is the only --rate-hz the image runs.

The records travel framed as the QEMU board's UART2 takes them (record_bridge.frame: A5 5A, length,
record, CRC-32); a reply frame that fails its CRC is counted and dropped here. Real time only: the
Due keeps its own clock. The simulator dates each reply's period on its own clock (ha_sil's
micros() is the host's CLOCK_MONOTONIC), so each tick of the Due is put on that clock before the
reply goes on (record_bridge.HaClock). --record-log writes a line a reply (record_bridge.
RecordBridge; the loop pass's time is in microseconds on the Due). SIGINT/SIGTERM, or the
simulator closing the socket, end it."""
import argparse
import os
import sys
import termios
import time
import tty

from hil import record_bridge

BAUD = termios.B115200  # the VN-200 port 1's rate; never 1200 on the native port (it erases the flash)


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
        if not record_bridge.wait_for(path, stop, max(0.0, deadline - time.monotonic())):
            return path
    return None


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--native", required=True, help="the Due's native USB port (e.g. /dev/ttyACM1)")
    ap.add_argument("--ins", required=True, help="the USB-serial adapter wired to the Due's RX1 (e.g. /dev/ttyUSB0)")
    ap.add_argument("--vn200", required=True, help="the simulator's VN-200 port 1 (a pty)")
    ap.add_argument("--lockstep", required=True, help="the simulator's control socket")
    ap.add_argument("--realtime", action="store_true")
    ap.add_argument("--rate-hz", type=float, default=None, help="the aircraft's (the only one the image runs)")
    ap.add_argument("--aircraft-dir", required=True, help="the aircraft folder the image was built from")
    ap.add_argument("--record-log", default=None)
    args, _ = ap.parse_known_args(argv)  # roslaunch's __name:= and __log:=
    if not args.realtime:
        print("ha_due: a Due keeps its own clock: it flies in real time only (--realtime)", file=sys.stderr)
        return 2
    refused = record_bridge.board_period_refused("ha_due", args.rate_hz, args.aircraft_dir)
    if refused is not None:
        return refused
    stop = record_bridge.stop_on_signals()
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
    chan = record_bridge.connect(args.lockstep, stop)
    if chan is None:
        print("ha_due: cannot connect to the simulator at %s" % args.lockstep, file=sys.stderr)
        return 1
    log = open(args.record_log, "w", buffering=1) if args.record_log else None
    bridge = record_bridge.RecordBridge(chan, native, ins, vn, log)
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
