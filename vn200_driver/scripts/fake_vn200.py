#!/usr/bin/env python3
"""A fake VectorNav VN-200 on a pseudo-terminal, for tests and bench work without hardware.

It answers the ASCII configuration commands as the sensor does (register writes are echoed,
$VNRRG,01 gives the model, bad checksums give $VNERR,03), streams binary output packets laid out
from the group/field masks written to register 75 at 800 Hz / divisor, and until register 6 is
set to 0 it streams the factory-default ASCII $VNYMR sentences. The port appears at --link, a
symlink to the current pty; --drop-after/--down-for simulate a USB unplug: the pty is closed,
the link removed, and a new pty linked after a pause. A real unplug may also power-cycle the
sensor, so the new port starts unconfigured and only streams binary once reconfigured.
With --baud the fake also has a serial speed: it reads the driver's port speed from the pty's
termios and neither hears nor answers a driver at another speed (real bytes at the wrong baud
are noise), until register 5 switches it; a power cycle restores --baud.
--capture FILE --packets N writes N binary packets to FILE instead (a replay capture).
Standard library only, so it runs under ROS's Python as well as the venv's. The packets and the register
conversation are vn200_sim.vn200_emulation's, shared with the HiL simulator (hil/).
"""
import argparse
import math
import os
import select
import signal
import sys
import time
import termios
import tty

# The packet and configuration code is shared with the HiL simulator; catkin's devel-space relay
# runs this file from elsewhere, so its own folder goes on the path.
from vn200_sim.vn200_emulation import (BAUD_CONSTANTS, Registers, Solution, binary_packet,  # noqa: E402
                             sentence)

NS_PER_WEEK = 604800 * 10**9
GPS_EPOCH_OFFSET_NS = 2170 * NS_PER_WEEK + 345600 * 10**9  # a Wednesday in GPS week 2170

# The simulated flight, shared with the checker: level-ish cruise, slow right turn.
LAT0_DEG, LON0_DEG, ALT0_M = 45.4642, 9.1900, 150.0
PITCH_DEG, ROLL_DEG = 2.0, -3.0


def yaw_deg(t):
    return (30.0 + 5.0 * t) % 360.0


def solution(t_s, origin=(LAT0_DEG, LON0_DEG, ALT0_M)):
    """The made-up flight at sensor time t_s, starting at origin (lat, lon in deg, alt in m)."""
    startup_ns = int(t_s * 1e9)
    return Solution(startup_ns=startup_ns, gps_ns=GPS_EPOCH_OFFSET_NS + startup_ns,
                    ypr_deg=(yaw_deg(t_s), PITCH_DEG, ROLL_DEG),
                    rate_radps=(0.01, -0.02, math.radians(5.0)),
                    lla=(origin[0] + 1e-5 * t_s, origin[1], origin[2]),
                    vel_ned_mps=(20.0, 1.0, -0.5), accel_mps2=(0.1, -0.3, -9.81))


class FakeSensor:
    def __init__(self, args):
        self.args = args
        self.t0 = time.monotonic()
        self.master = self.slave = None
        self.reset_config()

    def reset_config(self):
        self.registers = Registers(self.args.port, baud=self.args.baud,
                                   ha_owns_output_1=self.args.ha_owns_output_1)
        self.configured_count = 0

    @property
    def baud(self):
        return self.registers.baud

    def now_s(self):
        return time.monotonic() - self.t0

    def open_port(self):
        self.master, self.slave = os.openpty()
        tty.setraw(self.slave)
        tmp = self.args.link + ".tmp"
        if os.path.lexists(tmp):
            os.unlink(tmp)
        os.symlink(os.ttyname(self.slave), tmp)
        os.replace(tmp, self.args.link)
        self.inbuf = b""
        self.connected_at = self.now_s()
        log("port up at %s -> %s" % (self.args.link, os.ttyname(self.slave)))

    def close_port(self):
        for fd in (self.master, self.slave):
            if fd is not None:
                os.close(fd)
        self.master = self.slave = None
        if os.path.lexists(self.args.link):
            os.unlink(self.args.link)
        log("port down")

    def speed_matches(self):
        """Whether the driver's end of the pty is set to the fake sensor's baud rate."""
        if not self.baud:
            return True
        speed = termios.tcgetattr(self.slave)[5]
        return BAUD_CONSTANTS.get(speed) == self.baud

    def send(self, data):
        if not self.speed_matches():
            return  # the driver listens at another speed: it would see only noise
        try:
            os.write(self.master, data)
        except OSError:
            pass  # nobody reading and the pty buffer is full: a real UART drops bytes too

    def handle(self, line):
        reply, event = self.registers.handle(line)
        self.send(reply)
        if event is None:
            return
        if event[0] == "baud":
            if self.registers.baud:
                self.registers.baud = event[1]
                log("baud rate now %d" % event[1])
        elif event[0] == "refused":
            log("refused: " + event[1])
        elif event[0] == "output":
            self.configured_count += 1
            self.next_packet = self.now_s()
            self.sent = 0
            log(event[2])

    def run(self):
        self.open_port()
        next_ascii = 0.0
        while True:
            now = self.now_s()
            if (self.args.drop_after > 0 and self.master is not None
                    and now - self.connected_at > self.args.drop_after):
                self.close_port()
                time.sleep(self.args.down_for)
                self.reset_config()
                self.open_port()
                continue
            r, _, _ = select.select([self.master], [], [], 0.002)
            if r:
                try:
                    data = os.read(self.master, 4096)
                except OSError:
                    data = b""
                if self.speed_matches():
                    self.inbuf += data
                while b"\n" in self.inbuf:
                    raw, self.inbuf = self.inbuf.split(b"\n", 1)
                    line = raw.decode(errors="replace").strip()
                    if line.startswith("$"):
                        self.handle(line)
            if self.registers.ascii_async and now >= next_ascii:
                next_ascii = now + 0.025
                self.send(sentence("VNYMR,%+08.3f,%+08.3f,%+08.3f,+0.2100,+0.0200,+0.4300,"
                                   "+00.100,-00.300,-09.810,+0.010,-0.020,+0.087"
                                   % (yaw_deg(now), PITCH_DEG, ROLL_DEG)))
            divisor, groups, masks = self.registers.stream()
            if divisor and groups:
                period = divisor / 800.0
                burst = b""
                while self.next_packet <= now:
                    burst += binary_packet(groups, masks, solution(self.next_packet, self.args.origin))
                    self.sent += 1
                    if self.args.noise_every and self.sent % self.args.noise_every == 0:
                        bad = bytearray(binary_packet(groups, masks, solution(self.next_packet, self.args.origin)))
                        bad[len(bad) // 2] ^= 0x5A
                        burst += b"\x00\x13" + bytes(bad)  # line noise, then a corrupt packet
                    self.next_packet += period
                if burst:
                    self.send(burst)


def log(msg):
    print("fake_vn200: " + msg, flush=True)


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--link", help="path of the symlink to the pty the driver opens")
    p.add_argument("--drop-after", type=float, default=0.0,
                   help="seconds after each connect to simulate a USB unplug (0: never)")
    p.add_argument("--down-for", type=float, default=1.5, help="seconds the port stays gone")
    p.add_argument("--noise-every", type=int, default=0,
                   help="after every Nth packet inject noise and a corrupt packet (0: never)")
    p.add_argument("--baud", type=int, default=0,
                   help="the sensor's serial speed at power-up (0: ignore speeds)")
    p.add_argument("--port", type=int, default=2, choices=(1, 2),
                   help="which of the sensor's serial ports this pty is (the HP's: 2)")
    p.add_argument("--ha-owns-output-1", action="store_true",
                   help="register 75 is set up for the HA on port 1 and refuses writes")
    p.add_argument("--capture", help="write a binary capture to this file and exit")
    p.add_argument("--packets", type=int, default=100)
    p.add_argument("--rate-hz", type=float, default=50.0)
    p.add_argument("--origin", type=float, nargs=3, default=(LAT0_DEG, LON0_DEG, ALT0_M),
                   metavar=("LAT_DEG", "LON_DEG", "ALT_M"),
                   help="where the flight starts (two fakes on one master: two places)")
    args = p.parse_args([a for a in argv if not a.startswith("__")])  # drop roslaunch's __name:=
    if args.capture:
        groups, masks = 0x39, [0x15FB, 0, 0, 0x0618, 0x0100, 0x0600]
        with open(args.capture, "wb") as f:
            for i in range(args.packets):
                f.write(binary_packet(groups, masks, solution(10.0 + i / args.rate_hz)))
        return 0
    if not args.link:
        p.error("--link is required unless --capture is given")
    sensor = FakeSensor(args)

    def stop(*_):
        if sensor.master is not None:
            sensor.close_port()
        sys.exit(0)

    signal.signal(signal.SIGTERM, stop)
    signal.signal(signal.SIGINT, stop)
    sensor.run()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
