"""The VN-200 as the bytes on its serial port: binary output packets laid out from the group and
field masks of a binary output register, and the sensor's answers to the ASCII configuration
commands a driver sends (VN-200 User Manual). Shared by the fake sensor (fake_vn200.py, a made-up
flight for the driver's tests) and the HiL simulator (hil/, the flight dynamics' truth), so both
speak to the real `vn200` node and the HA exactly alike. Standard library only.
"""
import math
import struct
import termios

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
BASE_RATE_HZ = 800  # binary output rate = BASE_RATE_HZ / divisor
INS_STATUS_TRACKING_FIX = 0x0006  # mode 2 (tracking), GNSS fix

BAUD_CONSTANTS = {getattr(termios, "B%d" % b): b for b in
                  (9600, 19200, 38400, 57600, 115200, 230400, 460800, 921600)}


class Solution:
    """One output of the sensor: the values its binary fields carry (sensor units: deg, rad/s,
    m/s^2, gauss, kPa, degC, WGS84 ellipsoid height in m, NED m/s)."""

    def __init__(self, startup_ns, gps_ns, ypr_deg, rate_radps, lla, vel_ned_mps, accel_mps2,
                 mag_gauss=(0.21, 0.02, 0.43), temp_c=24.5, pressure_kpa=99.8,
                 ins_status=INS_STATUS_TRACKING_FIX, num_sats=9, gps_fix=3,
                 gps_pos_unc_m=(1.2, 1.2, 2.5), gps_vel_unc_mps=0.15, ypr_unc_deg=(0.8, 0.2, 0.2),
                 ins_pos_unc_m=2.0, ins_vel_unc_mps=0.1):
        self.startup_ns = startup_ns
        self.gps_ns = gps_ns
        self.ypr_deg = ypr_deg
        self.rate_radps = rate_radps
        self.lla = lla
        self.vel_ned_mps = vel_ned_mps
        self.accel_mps2 = accel_mps2
        self.mag_gauss = mag_gauss
        self.temp_c = temp_c
        self.pressure_kpa = pressure_kpa
        self.ins_status = ins_status
        self.num_sats = num_sats
        self.gps_fix = gps_fix
        self.gps_pos_unc_m = gps_pos_unc_m
        self.gps_vel_unc_mps = gps_vel_unc_mps
        self.ypr_unc_deg = ypr_unc_deg
        self.ins_pos_unc_m = ins_pos_unc_m
        self.ins_vel_unc_mps = ins_vel_unc_mps


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
    """Body relative to NED from yaw, pitch, roll [rad]; (x, y, z, w) as the sensor sends it."""
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    return (sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy,
            cr * cp * sy - sr * sp * cy, cr * cp * cy + sr * sp * sy)


def field_bytes(group, bit, s):
    """Little-endian value of one field of Solution s; zeros for fields not simulated."""
    yaw, pitch, roll = s.ypr_deg
    lla = struct.pack("<3d", *s.lla)
    vel = struct.pack("<3f", *s.vel_ned_mps)
    status = struct.pack("<H", s.ins_status)
    if group == 0:
        table = {
            0: lambda: struct.pack("<Q", s.startup_ns),
            1: lambda: struct.pack("<Q", s.gps_ns),
            3: lambda: struct.pack("<3f", *s.ypr_deg),
            4: lambda: struct.pack("<4f", *quat_ned(math.radians(yaw), math.radians(pitch),
                                                    math.radians(roll))),
            5: lambda: struct.pack("<3f", *s.rate_radps),
            6: lambda: lla, 7: lambda: vel,
            8: lambda: struct.pack("<3f", *s.accel_mps2),
            10: lambda: struct.pack("<5f", *s.mag_gauss, s.temp_c, s.pressure_kpa),
            12: lambda: status,
        }
    elif group == 1:
        table = {0: lambda: struct.pack("<Q", s.startup_ns),
                 2: lambda: struct.pack("<Q", s.gps_ns % NS_PER_WEEK),
                 3: lambda: struct.pack("<H", s.gps_ns // NS_PER_WEEK)}
    elif group == 3:
        table = {3: lambda: struct.pack("<B", s.num_sats), 4: lambda: struct.pack("<B", s.gps_fix),
                 9: lambda: struct.pack("<3f", *s.gps_pos_unc_m),
                 10: lambda: struct.pack("<f", s.gps_vel_unc_mps)}
    elif group == 4:
        table = {8: lambda: struct.pack("<3f", *s.ypr_unc_deg)}
    elif group == 5:
        table = {0: lambda: status, 1: lambda: lla, 4: lambda: vel,
                 9: lambda: struct.pack("<f", s.ins_pos_unc_m),
                 10: lambda: struct.pack("<f", s.ins_vel_unc_mps)}
    else:
        table = {}
    make = table.get(bit)
    return make() if make is not None else bytes(FIELD_SIZES[group][bit])


def binary_packet(groups, masks, solution):
    body = bytearray([groups])
    payload = bytearray()
    for g in range(6):
        if groups & (1 << g):
            m = masks[g]
            body += struct.pack("<H", m)
            for b in range(16):
                if m & (1 << b):
                    payload += field_bytes(g, b, solution)
    body += payload
    return b"\xfa" + bytes(body) + struct.pack(">H", crc16(body))


def packet_length(groups, masks):
    n = 1 + 1 + 2  # sync, groups, CRC
    for g in range(6):
        if groups & (1 << g):
            n += 2 + sum(FIELD_SIZES[g][b] for b in range(16) if masks[g] & (1 << b))
    return n


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


class Registers:
    """The sensor's configuration as one of its serial ports sees it. Registers 75-77 (binary
    outputs 1-3) are global to the sensor; each output's AsyncMode routes it to port 1, port 2 or
    both, and a port streams the outputs routed to it (one stream per port is all a driver asks
    for: the first routed output feeds it). With ha_owns_output_1, register 75 was set up for the
    HA on port 1 (as on the aircraft, output_1) and a write to it is refused, so a driver that
    would take it over fails."""

    def __init__(self, port, baud=0, ha_owns_output_1=False, output_1=(1, 8, 0x01, [0x0008, 0, 0, 0, 0, 0])):
        self.port = port
        self.baud = baud
        self.ascii_async = True
        self.ha_owns_output_1 = ha_owns_output_1
        self.outputs = {}  # register -> (mode, divisor, groups, masks)
        if ha_owns_output_1:
            self.outputs[75] = output_1
        self.divisor, self.groups, self.masks = 0, 0, [0] * 6

    def stream(self):
        """(divisor, groups, masks) of the stream on this port; divisor 0: none."""
        return self.divisor, self.groups, self.masks

    def handle(self, line):
        """Answers one ASCII command line. Returns (reply bytes, event): event is None, ("baud",
        new baud: switch after the reply), ("output", register, text) or ("refused", text)."""
        if not ascii_ok(line):
            return sentence("VNERR,03"), None
        body = line[1:].rsplit("*", 1)[0]
        parts = body.split(",")
        cmd = parts[0]
        try:
            if cmd == "VNRRG" and int(parts[1]) == 1:
                return sentence("VNRRG,01,VN-200T-CR"), None
            if cmd == "VNWRG" and int(parts[1]) == 6:
                self.ascii_async = int(parts[2]) != 0
                return sentence(body), None
            if cmd == "VNWRG" and int(parts[1]) == 5:
                new_baud = int(parts[2])
                if new_baud not in BAUD_CONSTANTS.values():
                    raise ValueError("unsupported baud")
                return sentence(body), ("baud", new_baud)  # answered at the old speed
            if cmd == "VNWRG" and int(parts[1]) == 75 and self.ha_owns_output_1:
                return sentence("VNERR,09"), ("refused", "register 75 is the HA's binary output (port 1)")
            if cmd == "VNWRG" and int(parts[1]) in (75, 76, 77):
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
                          (self.outputs[r] for r in sorted(self.outputs)) if md & self.port]
                self.divisor, self.groups, self.masks = routed[0] if routed else (0, 0, [0] * 6)
                text = ("binary output %d (register %d) configured: mode %d groups %02X masks %s "
                        "divisor %d%s" % (reg - 74, reg, mode, groups,
                                          " ".join("%04X" % m for m in masks), divisor,
                                          "" if mode & self.port else
                                          " (not routed to this port %d)" % self.port))
                return sentence(body), ("output", reg, text)
            return sentence("VNERR,04"), None
        except (ValueError, IndexError):
            return sentence("VNERR,07"), None
