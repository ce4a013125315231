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
Standard library only, so it runs with /usr/bin/python3 anywhere.
"""
import argparse
import math
import os
import select
import signal
import struct
import sys
import time
import termios
import tty

# Field sizes [bytes] per group, per mask bit (VN-200 User Manual, binary output groups).
FIELD_SIZES = [
    [8, 8, 8, 12, 16, 12, 24, 12, 12, 24, 20, 28, 2, 4, 8, 0],  # Common
    [8, 8, 8, 2, 8, 8, 8, 4, 4, 1, 0, 0, 0, 0, 0, 0],  # Time
    [2, 12, 12, 12, 4, 4, 16, 12, 12, 12, 12, 0, 0, 0, 0, 0],  # IMU
    [8, 8, 2, 1, 1, 24, 24, 12, 12, 12, 4, 4, 0, 0, 0, 0],  # GPS
    [2, 12, 16, 36, 12, 12, 12, 12, 12, 0, 0, 0, 0, 0, 0, 0],  # Attitude
    [2, 24, 24, 12, 12, 12, 12, 12, 12, 4, 4, 0, 0, 0, 0, 0],  # INS
]
NS_PER_WEEK = 604800 * 10**9
GPS_EPOCH_OFFSET_NS = 2170 * NS_PER_WEEK + 345600 * 10**9  # a Wednesday in GPS week 2170

# The simulated flight, shared with the checker: level-ish cruise, slow right turn.
LAT0_DEG, LON0_DEG, ALT0_M = 45.4642, 9.1900, 150.0
PITCH_DEG, ROLL_DEG = 2.0, -3.0


def yaw_deg(t):
    return (30.0 + 5.0 * t) % 360.0


def crc16(data):
    crc = 0
    for b in data:
        crc = ((crc >> 8) | (crc << 8)) & 0xFFFF
        crc ^= b
        crc ^= (crc & 0xFF) >> 4
        crc ^= (crc << 12) & 0xFFFF
        crc ^= (crc & 0xFF) << 5
    return crc


def xor8(data):
    x = 0
    for b in data:
        x ^= b
    return x


def sentence(body):
    return ("$%s*%02X\r\n" % (body, xor8(body.encode()))).encode()


def quat_ned(yaw, pitch, roll):
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    return (sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy,
            cr * cp * sy - sr * sp * cy, cr * cp * cy + sr * sp * sy)


def field_bytes(group, bit, t_s):
    """Little-endian value of one field at sensor time t_s; zeros for fields not simulated."""
    yaw = yaw_deg(t_s)
    ypr = struct.pack("<3f", yaw, PITCH_DEG, ROLL_DEG)
    lla = struct.pack("<3d", LAT0_DEG + 1e-5 * t_s, LON0_DEG, ALT0_M)
    vel = struct.pack("<3f", 20.0, 1.0, -0.5)
    startup_ns = int(t_s * 1e9)
    gps_ns = GPS_EPOCH_OFFSET_NS + startup_ns
    table = {
        (0, 0): struct.pack("<Q", startup_ns), (0, 1): struct.pack("<Q", gps_ns),
        (0, 3): ypr,
        (0, 4): struct.pack("<4f", *quat_ned(math.radians(yaw), math.radians(PITCH_DEG),
                                             math.radians(ROLL_DEG))),
        (0, 5): struct.pack("<3f", 0.01, -0.02, math.radians(5.0)),
        (0, 6): lla, (0, 7): vel,
        (0, 8): struct.pack("<3f", 0.1, -0.3, -9.81),
        (0, 10): struct.pack("<5f", 0.21, 0.02, 0.43, 24.5, 99.8),
        (0, 12): struct.pack("<H", 0x0006),  # INS tracking (mode 2), GNSS fix
        (1, 0): struct.pack("<Q", startup_ns), (1, 2): struct.pack("<Q", gps_ns % NS_PER_WEEK),
        (1, 3): struct.pack("<H", gps_ns // NS_PER_WEEK),
        (3, 3): struct.pack("<B", 9), (3, 4): struct.pack("<B", 3),
        (3, 9): struct.pack("<3f", 1.2, 1.2, 2.5), (3, 10): struct.pack("<f", 0.15),
        (4, 8): struct.pack("<3f", 0.8, 0.2, 0.2),
        (5, 0): struct.pack("<H", 0x0006), (5, 1): lla, (5, 4): vel,
        (5, 9): struct.pack("<f", 2.0), (5, 10): struct.pack("<f", 0.1),
    }
    return table.get((group, bit), bytes(FIELD_SIZES[group][bit]))


def binary_packet(groups, masks, t_s):
    body = bytearray([groups])
    payload = bytearray()
    for g in range(6):
        if groups & (1 << g):
            m = masks[g]
            body += struct.pack("<H", m)
            for b in range(16):
                if m & (1 << b):
                    payload += field_bytes(g, b, t_s)
    body += payload
    return b"\xfa" + bytes(body) + struct.pack(">H", crc16(body))


def ascii_ok(line):
    if not line.startswith("$") or "*" not in line:
        return False
    body, ck = line[1:].rsplit("*", 1)
    if ck == "XX":
        return True
    try:
        if len(ck) == 2:
            return int(ck, 16) == xor8(body.encode())
        if len(ck) == 4:
            return int(ck, 16) == crc16(body.encode())
    except ValueError:
        pass
    return False


class FakeSensor:
    def __init__(self, args):
        self.args = args
        self.t0 = time.monotonic()
        self.master = self.slave = None
        self.reset_config()

    def reset_config(self):
        self.baud = self.args.baud
        self.ascii_async = True
        # Registers 75-77 are global to the sensor; each output's AsyncMode routes it to port 1,
        # port 2 or both. This fake is the port named by --port: it streams the outputs routed
        # to it. With --ha-owns-output-1, register 75 was set up for the HA on port 1 (as on the
        # aircraft) and a write to it is refused, so a driver that would take it over fails here.
        self.outputs = {}  # register -> (mode, divisor, groups, masks)
        if self.args.ha_owns_output_1:
            self.outputs[75] = (1, 8, 0x01, [0x0008, 0, 0, 0, 0, 0])
        self.groups = 0
        self.masks = [0] * 6
        self.divisor = 0
        self.configured_count = 0

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
        if not ascii_ok(line):
            self.send(sentence("VNERR,03"))
            return
        body = line[1:].rsplit("*", 1)[0]
        parts = body.split(",")
        cmd = parts[0]
        try:
            if cmd == "VNRRG" and int(parts[1]) == 1:
                self.send(sentence("VNRRG,01,VN-200T-CR"))
            elif cmd == "VNWRG" and int(parts[1]) == 6:
                self.ascii_async = int(parts[2]) != 0
                self.send(sentence(body))
            elif cmd == "VNWRG" and int(parts[1]) == 5:
                new_baud = int(parts[2])
                if new_baud not in BAUD_CONSTANTS.values():
                    raise ValueError("unsupported baud")
                self.send(sentence(body))  # answered at the old speed, then switched
                if self.baud:
                    self.baud = new_baud
                    log("baud rate now %d" % new_baud)
            elif cmd == "VNWRG" and int(parts[1]) == 75 and self.args.ha_owns_output_1:
                log("refused: register 75 is the HA's binary output (port 1)")
                self.send(sentence("VNERR,09"))
            elif cmd == "VNWRG" and int(parts[1]) in (75, 76, 77):
                reg = int(parts[1])
                mode, divisor, groups = int(parts[2]), int(parts[3]), int(parts[4], 16)
                masks, i = [0] * 6, 5
                for g in range(6):
                    if groups & (1 << g):
                        masks[g] = int(parts[i], 16)
                        i += 1
                        if any((masks[g] >> b) & 1 and FIELD_SIZES[g][b] == 0 for b in range(16)):
                            raise ValueError("undocumented field")
                if i != len(parts) or groups & ~0x3F or divisor < 1 or mode not in (0, 1, 2, 3):
                    raise ValueError("bad binary output")
                self.outputs[reg] = (mode, divisor, groups, masks)
                routed = [(d, g, m) for (md, d, g, m) in
                          (self.outputs[r] for r in sorted(self.outputs))
                          if md & self.args.port]
                # One stream per port is all the node asks for; the first routed output feeds it.
                self.divisor, self.groups, self.masks = routed[0] if routed else (0, 0, [0] * 6)
                self.configured_count += 1
                self.next_packet = self.now_s()
                self.sent = 0
                self.send(sentence(body))
                log("binary output %d (register %d) configured: mode %d groups %02X masks %s "
                    "divisor %d%s" % (reg - 74, reg, mode, groups, " ".join("%04X" % m for m in masks),
                                      divisor, "" if mode & self.args.port else
                                      " (not routed to this port %d)" % self.args.port))
            else:
                self.send(sentence("VNERR,04"))
        except (ValueError, IndexError):
            self.send(sentence("VNERR,07"))

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
            if self.ascii_async and now >= next_ascii:
                next_ascii = now + 0.025
                self.send(sentence("VNYMR,%+08.3f,%+08.3f,%+08.3f,+0.2100,+0.0200,+0.4300,"
                                   "+00.100,-00.300,-09.810,+0.010,-0.020,+0.087"
                                   % (yaw_deg(now), PITCH_DEG, ROLL_DEG)))
            if self.divisor and self.groups:
                period = self.divisor / 800.0
                burst = b""
                while self.next_packet <= now:
                    burst += binary_packet(self.groups, self.masks, self.next_packet)
                    self.sent += 1
                    if self.args.noise_every and self.sent % self.args.noise_every == 0:
                        bad = bytearray(binary_packet(self.groups, self.masks, self.next_packet))
                        bad[len(bad) // 2] ^= 0x5A
                        burst += b"\x00\x13" + bytes(bad)  # line noise, then a corrupt packet
                    self.next_packet += period
                if burst:
                    self.send(burst)


BAUD_CONSTANTS = {getattr(termios, "B%d" % b): b for b in
                  (9600, 19200, 38400, 57600, 115200, 230400, 460800, 921600)}


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
    args = p.parse_args([a for a in argv if not a.startswith("__")])  # drop roslaunch's __name:=
    if args.capture:
        groups, masks = 0x39, [0x15FB, 0, 0, 0x0618, 0x0100, 0x0600]
        with open(args.capture, "wb") as f:
            for i in range(args.packets):
                f.write(binary_packet(groups, masks, 10.0 + i / args.rate_hz))
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
