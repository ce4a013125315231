"""The aircraft's sensors at their real interfaces, from the flight-dynamics truth.

- VN-200 port 2 (the HP's `vn200` node): a pty that answers the node's ASCII configuration as the
  sensor does and streams the binary output the node writes (Binary Output 2, register 76),
  with vn200_driver/src/vn200_sim/vn200_emulation.py, the fake sensor's own register code; the packets
  are built by the C99 encoder (vn200_driver/encode, one call each through vn200_encode.py),
  whose bytes are the fake sensor's Python encoder's (vn200_driver/test/test_vn200_encode.py).
- VN-200 port 1 (the HA): Binary Output 1 as configured once on the bench and saved to the
  sensor's flash (arduino_ha/README.md, "VN-200"): Common YPR, angular rate, position, velocity
  and INS status, and GPS fix, at 100 Hz, 115200 baud.
- The HA's AMS5812 airspeed sensor, battery and RC receiver, as the Due's board layer reads them.

Noise is seeded per stream (the same seed gives the same bytes). The VN-200 figures are the
datasheet's headline accuracies (attitude 0.03 deg pitch/roll and 0.2 deg heading RMS, position
1.0 m horizontal / 1.5 m vertical RMS, velocity 0.05 m/s RMS, gyro 0.0035 deg/s/sqrt(Hz), accel
0.14 mg/sqrt(Hz)); the INS's errors are slow (a Kalman filter's output), so attitude, position
and velocity errors are first-order Gauss-Markov processes with those RMS values, rates and
accelerations white noise over the output bandwidth. Latency: a packet's solution is the truth at
its sensor time minus the time its bytes take on the wire.
"""
import math
import os
import random

from hil import ins_noise, ptys  # noqa: E402
from stack_common import geo  # noqa: E402
from stack_common.units import FT_PER_M, G_MPS2  # noqa: E402
from vn200_sim.vn200_emulation import (INS_STATUS_TRACKING_FIX, NS_PER_WEEK, Registers, Solution,  # noqa: E402
                             packet_length)
from vn200_sim.vn200_encode import PacketEncoder  # noqa: E402

GPS_EPOCH_OFFSET_NS = 2390 * NS_PER_WEEK  # a GPS week of 2025; only its consistency matters
SENSOR_STARTUP_S = 5.0  # the VN-200 was powered this long before simulation time 0

# Binary Output 1, the HA's (arduino_ha/README.md): mode 1 (port 1), divisor 8 (100 Hz),
# groups Common | GPS, Common YPR | angular rate | position | velocity | acceleration | INS status,
# GPS fix.
HA_OUTPUT_1 = (1, 8, 0x09, [0x0008 | 0x0020 | 0x0040 | 0x0080 | 0x0100 | 0x1000, 0, 0, 0x0010, 0, 0])
HA_VN200_BAUD = 115200  # DUE_VN200_BAUD
HP_VN200_BAUD = 921600  # the flight launch's vn200_baud


class GaussMarkov:
    """First-order Gauss-Markov error with stationary RMS sigma and time constant tau_s."""

    def __init__(self, rng, sigma, tau_s):
        self.rng, self.sigma, self.tau_s = rng, sigma, tau_s
        self.x = rng.gauss(0.0, sigma)
        self.dt_s = None  # the step the coefficients below are for: every caller keeps one

    def coefficients(self, dt_s):
        """(a, k) of x' = a x + k n for a step of dt_s, n a unit normal draw."""
        if dt_s != self.dt_s:
            self.dt_s = dt_s
            self.a = math.exp(-dt_s / self.tau_s)
            self.k = self.sigma * math.sqrt(1.0 - self.a * self.a)
        return self.a, self.k

    def step(self, dt_s):
        a, k = self.coefficients(dt_s)
        self.x = a * self.x + k * self.rng.gauss(0.0, 1.0)
        return self.x


class InsSolutionErrors:
    """The slow errors of the VN-200's one navigation filter (attitude, position, velocity), on a
    grid of its 800 Hz IMU clock: both serial ports output the same solution, so both streams read
    the same errors at the same sensor time (one home latched from port 1 is then the same point
    port 2 measures from). Each grid step is drawn once, in order, whichever port asks first, so a
    seed still fixes every byte. Drawn in C (hil.ins_noise): random.gauss's numbers, to the bit."""

    GRID_HZ = 800.0

    def __init__(self, seed):
        r = random.Random("%s/ins_solution" % seed)
        # The processes' initial values are drawn here, in this order (attitude, position,
        # velocity); the grid step is the same for all nine.
        chans = ([GaussMarkov(r, 0.2, 20.0), GaussMarkov(r, 0.03, 20.0), GaussMarkov(r, 0.03, 20.0)] +
                 [GaussMarkov(r, 1.0 / math.sqrt(2.0), 60.0), GaussMarkov(r, 1.0 / math.sqrt(2.0), 60.0),
                  GaussMarkov(r, 1.5, 60.0)] +
                 [GaussMarkov(r, 0.05, 5.0) for _ in range(3)])
        ak = [e.coefficients(1.0 / self.GRID_HZ) for e in chans]
        self.noise = ins_noise.InsNoise(r, [a for a, _ in ak], [k for _, k in ak], [e.x for e in chans])
        self.keep = self.noise.keep
        self.index = None  # grid index of the newest value

    def draw_until(self, sensor_t_s):
        """Draws the grid up to sensor time sensor_t_s ahead of the packets that will read it:
        the values are those at() would draw then. Nothing before the first packet's request,
        which fixes where the grid starts."""
        if self.index is not None:
            self._draw_to(int(math.floor(sensor_t_s * self.GRID_HZ + 1e-6)))

    def at(self, sensor_t_s):
        """(attitude, position, velocity) errors at sensor time sensor_t_s."""
        k = int(math.floor(sensor_t_s * self.GRID_HZ + 1e-6))
        if self.index is None:
            self.index = self.first = k
            self.noise.start(k)
        self._draw_to(k)
        # Older than remembered (never in a flight) or than the first request: the oldest kept.
        x = self.noise.at(max(k, self.first, self.index - self.keep + 1))
        return x[0:3], x[3:6], x[6:9]

    def _draw_to(self, k):
        if self.index < k:
            self.noise.draw_to(k)
            self.index = k


class Vn200Errors:
    """The errors of one VN-200 output stream: the navigation filter's (shared by every stream,
    InsSolutionErrors) plus the rate and acceleration noise of this stream's own samples."""

    def __init__(self, seed, name, rate_hz, solution_errors):
        self.rng = random.Random("%s/%s" % (seed, name))
        self.shared = solution_errors
        bw = math.sqrt(rate_hz / 2.0)
        self.gyro_sigma = math.radians(0.0035) * bw
        self.accel_sigma = 0.14e-3 * G_MPS2 * bw

    def solution(self, truth, sensor_t_s, dt_s):
        r = self.rng
        att, pos, vel = self.shared.at(sensor_t_s)
        # The solution's position error placed about the truth by the stack's one flat earth
        # (geo_wgs84.c), the longitude wrapped across the antimeridian as the VN-200 reports it.
        lat, lon, _ = geo.Ref(truth.lat_deg, truth.lon_deg).from_neu_m(pos[0], pos[1])
        ypr = ((truth.heading_deg + att[0]) % 360.0, truth.pitch_deg + att[1], truth.roll_deg + att[2])
        if ypr[0] > 180.0:
            ypr = (ypr[0] - 360.0, ypr[1], ypr[2])  # the VN-200 reports yaw in -180..180
        rates = (truth.p_rad_s + r.gauss(0.0, self.gyro_sigma), truth.q_rad_s + r.gauss(0.0, self.gyro_sigma),
                 truth.r_rad_s + r.gauss(0.0, self.gyro_sigma))
        acc = tuple(a + r.gauss(0.0, self.accel_sigma) for a in truth.accel_body_mps2)
        startup_ns = int(round((sensor_t_s + SENSOR_STARTUP_S) * 1e9))
        return Solution(startup_ns=startup_ns, gps_ns=GPS_EPOCH_OFFSET_NS + startup_ns,
                        ypr_deg=ypr, rate_radps=rates, lla=(lat, lon, truth.alt_msl_m + pos[2]),
                        vel_ned_mps=(truth.vn_mps + vel[0], truth.ve_mps + vel[1], truth.vd_mps + vel[2]),
                        accel_mps2=acc, mag_gauss=tuple(truth.mag_body_gauss),
                        temp_c=truth.temperature_c, pressure_kpa=truth.pressure_pa / 1000.0,
                        ins_status=INS_STATUS_TRACKING_FIX, num_sats=10, gps_fix=3)


class Pty:
    """A pseudo-terminal whose slave is published under link (a symlink), like a USB serial
    device; the simulator holds the master end."""

    def __init__(self, link):
        self.link = link
        self.master, self.slave = ptys.open_raw()
        ptys.publish(os.ttyname(self.slave), link)
        self.written = 0

    def write(self, data):
        """Writes all of data (the reader drains the pty every step; a full buffer is waited out)."""
        view = memoryview(data)
        while view:
            try:
                n = os.write(self.master, view)
            except BlockingIOError:
                n = 0
            if n == 0:
                import select
                select.select([], [self.master], [], 0.05)
                continue
            view = view[n:]
            self.written += n

    def read(self):
        try:
            return os.read(self.master, 4096)
        except (BlockingIOError, OSError):
            return b""

    def close(self):
        for fd in (self.master, self.slave):
            try:
                os.close(fd)
            except OSError:
                pass
        if os.path.lexists(self.link):
            os.unlink(self.link)


class Vn200Port:
    """One of the VN-200's serial ports as a pty: answers ASCII commands (port 2, the HP's) and
    streams the binary output routed to it at its rate, on simulation time."""

    def __init__(self, link, port, seed, baud, fixed_output=None, solution_errors=None):
        """solution_errors: the INS's InsSolutionErrors, shared with the other port (one filter);
        a port made alone gets its own."""
        self.solution_errors = solution_errors if solution_errors is not None else InsSolutionErrors(seed)
        self.pty = Pty(link)
        self.registers = Registers(port, baud=0, ha_owns_output_1=True)
        if fixed_output is not None:
            self.registers.outputs[75] = fixed_output
            self.registers.divisor, self.registers.groups, self.registers.masks = fixed_output[1:]
            self.registers.ascii_async = False
        self.baud = baud
        self.seed = seed
        self.errors = None
        self.inbuf = b""
        self.next_index = None  # index of the next packet: sensor time = index * period
        self.packets = 0
        self.log = []
        self.on_written = None  # on_written(index of the first packet, count) after each write
        self.encoder = None  # PacketEncoder of the stream (groups, masks) it was made for
        self.solution_filter = None  # solution_filter(sensor_t_s, solution) -> solution (faults)

    def service_commands(self):
        """Answers whatever ASCII commands the driver wrote (any time, also while time stands)."""
        data = self.pty.read()
        if not data:
            return
        self.inbuf += data
        while b"\n" in self.inbuf:
            raw, self.inbuf = self.inbuf.split(b"\n", 1)
            line = raw.decode(errors="replace").strip()
            if line.startswith("$"):
                reply, event = self.registers.handle(line)
                self.pty.write(reply)
                if event is not None and event[0] == "output":
                    self.log.append(event[2])
                    self.errors = None  # a new stream: errors drawn afresh for it

    def configured(self):
        divisor, groups, _ = self.registers.stream()
        return bool(divisor and groups)

    def rate_hz(self):
        return 800.0 / self.registers.stream()[0]

    def latency_s(self):
        divisor, groups, masks = self.registers.stream()
        return packet_length(groups, masks) * 10.0 / self.baud

    def emit_until(self, t_s, truth_at):
        """Writes the packets whose sensor time is in (last, t_s]; truth_at(t) gives the truth the
        sensor had at time t. Returns the number of packets written."""
        if not self.configured():
            return 0
        divisor, groups, masks = self.registers.stream()
        rate = 800.0 / divisor
        if self.errors is None:
            self.errors = Vn200Errors(self.seed, "port%d/%d/%d" % (self.registers.port, divisor, groups), rate,
                                      self.solution_errors)
            self.next_index = int(math.floor(t_s * rate + 1e-9))
        if self.encoder is None or self.encoder_stream != (groups, tuple(masks)):
            self.encoder, self.encoder_stream = PacketEncoder(groups, masks), (groups, tuple(masks))
            self.encoder_latency_s = self.latency_s()
        out = bytearray()
        n = 0
        lat = self.encoder_latency_s
        first = self.packets
        while self.next_index / rate <= t_s + 1e-9:
            ts = self.next_index / rate
            sol = self.errors.solution(truth_at(ts - lat), ts, 1.0 / rate)
            if self.solution_filter is not None:
                sol = self.solution_filter(ts, sol)
            out += self.encoder.packet(sol)
            self.next_index += 1
            n += 1
        if out:
            self.pty.write(bytes(out))
            self.packets += n
            if self.on_written is not None:
                self.on_written(first, n)
        return n

    def skip_until(self, t_s):
        """The packets whose sensor time is in (last, t_s] are lost (a cut serial line): none is
        written, and the stream goes on from t_s as if they had been."""
        if not self.configured() or self.next_index is None:
            return 0
        rate = self.rate_hz()
        n = 0
        while self.next_index / rate <= t_s + 1e-9:
            self.next_index += 1
            n += 1
        return n

    def close(self):
        self.pty.close()


def probe_airspeed_mps(truth):
    """The airspeed the pitot probe measures: the part of the relative wind along the probe.

    The probe points along body x, so it feels the air-relative velocity's body-x component
    u = V cos(alpha) cos(beta) (wind and gusts included: JSBSim's alpha and beta are of the
    air-relative velocity), and its differential pressure is the impact pressure of that
    component, qc (u / V)^2 = qc cos(alpha)^2 cos(beta)^2. The impact pressure qc is JSBSim's
    own through its calibrated airspeed (qc = rho0 vc^2 / 2 at these speeds), so the density is
    the FDM's, where the aircraft flies: at altitude or on a hot day IAS reads below TAS.
    Sideslip and high alpha read low (14 deg of alpha: 6 % of the pressure, 3 % of the speed);
    flow from behind the probe (|alpha| or |beta| past 90 deg: parked tail to the wind) reads 0,
    the sensor's negative pressure clipped. The choice is the plain component model: a real
    pitot-static head is flat to some 15 deg and falls off faster beyond, so this reads a little
    low at moderate angles and a little high past the stall; with alpha = beta = 0 it reads
    exactly the calibrated airspeed, as before. Not modelled: the probe's offset from the CG
    (rotation adds p x r, under 1 % here), position error, compressibility beyond JSBSim's qc."""
    axial = math.cos(math.radians(truth.alpha_deg)) * math.cos(math.radians(truth.beta_deg))
    if not axial > 0.0:
        return 0.0
    return truth.airspeed_cal_mps * axial


class Ams5812:
    """The HA's differential-pressure airspeed sensor (AMS 5812-0003-D, 0..2068.43 Pa) as the
    Due's board layer reads it: counts with an offset and noise, then the datasheet's transfer
    function and v = sqrt(2 dp / rho0) (arduino_ha/src/board_due/ams5812.c). Fed the probe's
    airspeed (probe_airspeed_mps): sea-level dynamic pressure of it is what the probe feels."""

    P_MAX_PA = 2068.43
    COUNTS_MIN, COUNTS_MAX = 3277, 29491
    RHO0 = 1.225

    def __init__(self, seed):
        self.rng = random.Random("%s/ams5812" % seed)
        self.offset_pa = self.rng.gauss(0.0, 2.0)
        self.noise_pa = 0.5

    def read_ftps(self, airspeed_cal_mps):
        dp = 0.5 * self.RHO0 * airspeed_cal_mps * airspeed_cal_mps + self.offset_pa + self.rng.gauss(0.0, self.noise_pa)
        counts = int(round(self.COUNTS_MIN + dp / self.P_MAX_PA * (self.COUNTS_MAX - self.COUNTS_MIN)))
        counts = max(0, min(32767, counts))
        dp_read = (counts - self.COUNTS_MIN) / float(self.COUNTS_MAX - self.COUNTS_MIN) * self.P_MAX_PA
        if not dp_read > 0.0:
            return 0.0
        return math.sqrt(2.0 * dp_read / self.RHO0) * FT_PER_M


class Battery:
    """A 3S LiPo through the Due's 47k/10k divider and 12-bit ADC: slowly discharging."""

    def __init__(self, seed):
        self.rng = random.Random("%s/battery" % seed)

    def read_v(self, t_s, throttle):
        v = 12.6 - 0.002 * t_s - 0.4 * throttle + self.rng.gauss(0.0, 0.01)
        counts = max(0, min(4095, int(round(v / 5.7 / 3.3 * 4095.0))))
        return counts * 3.3 / 4095.0 * 5.7
