"""What the stories of the HA in the loop share, on either board (the host SIL, ha_sil; the QEMU
board, hil/ha_qemu.py): the parked aircraft its INS sees, the PIL image built for a run, and a rig
driving the QEMU board as the simulator and the HP would (used by test_pil_qemu.py,
test_realtime_crash.py and hil/bench/bench_pil.py)."""
import os
import struct
import subprocess
import tempfile
import time
import zlib

from stack_tools.paths import ROOT  # noqa: E402
from hil import ha_channel, ha_qemu, sensors  # noqa: E402
from stack_testing.wire_tap import frame, split_frames  # noqa: E402

HP, HA, MANUAL = 0, 1, 4  # DecisionStatus.CONTROLLER_*
CIC, PIC = (1100, 1500, 1500, 1500, 1000), (1100, 1800, 1500, 1500, 2000)
SUBSCRIBER_INFO = 1  # rosserial's topic id of a device's subscriber announcement


class Parked:
    """Truth of an aircraft parked at a field (what the HA's INS sees before take-off)."""
    lat_deg, lon_deg, alt_msl_m = 38.95, -95.26, 260.0
    vn_mps = ve_mps = vd_mps = 0.0
    roll_deg, pitch_deg, heading_deg = 0.0, 2.0, 30.0
    p_rad_s = q_rad_s = r_rad_s = 0.0
    accel_body_mps2 = (0.0, 0.0, -9.81)
    mag_body_gauss = (0.2, 0.0, 0.45)
    temperature_c, pressure_pa = 20.0, 98000.0


def build_pil_image(out_dir):
    """The firmware for QEMU's mps2-an385, built afresh (make pil-image's script, about 10 s)."""
    subprocess.run(["bash", os.path.join(ROOT, "arduino_ha", "pil", "build_pil_image.sh"), out_dir],
                   check=True, stdout=subprocess.DEVNULL)
    return os.path.join(out_dir, "ha_pil.elf")


class PilRig:
    """The QEMU board with the simulator's VN-200 on its INS UART and the HP's end of its link."""

    def __init__(self, image, icount=False):
        d = tempfile.mkdtemp(prefix="pil_")
        self.vn = sensors.Vn200Port(os.path.join(d, "ha_vn200"), 1, seed=7,
                                    baud=sensors.HA_VN200_BAUD, fixed_output=sensors.HA_OUTPUT_1)
        self.board = ha_qemu.QemuBoard(image, os.path.join(d, "ha_vn200"), icount).start()
        self.host = os.open(self.board.hp_pty, os.O_RDWR | os.O_NOCTTY | os.O_NONBLOCK)  # the HP's end
        self.from_ha = bytearray()

    def step(self, k, rc=CIC, wait_for=None, wait_ms=2000, truth=Parked):
        self.vn.emit_until(k * 0.01, lambda t: truth)
        rec = self.record(k, rc, wait_for, wait_ms)
        reply, dropped, ticks = self.board.exchange(rec)
        return ha_channel.decode_reply(reply), dropped, ticks

    def record(self, k, rc=CIC, wait_for=None, wait_ms=2000):
        flags = ha_channel.RC_VALID | ha_channel.AIRSPEED_OK | ha_channel.BATTERY_OK | \
            (ha_channel.WAIT_COMMAND if wait_for is not None else 0)
        return ha_channel.STEP.pack(ha_channel.MAGIC_STEP, ha_channel.VERSION, flags, k * 10000,
                                    self.vn.pty.written, wait_for or 0, wait_ms, *rc, 0, 0.0, 12.4)

    def frames_from_ha(self):
        try:
            while True:
                self.from_ha += os.read(self.host, 4096)
        except BlockingIOError:
            pass
        return split_frames(self.from_ha)

    def close(self):
        os.close(self.host)
        self.board.stop()
        self.vn.close()


def servo_command(seq, elevator_deg):
    fields = struct.pack("<III6fBB", seq, 1700000000, seq * 10000000 % 1000000000, 0.0, elevator_deg,
                         1.5, -0.5, 2.0, 0.0, 1, 1)
    return fields + struct.pack("<I", zlib.crc32(fields))


def negotiate(rig, k):
    """The host's topic request; returns the topic id the HA takes ServoCommands on."""
    os.write(rig.host, frame(0, b""))
    for k in range(k, k + 50):
        rig.step(k)
        for f in rig.frames_from_ha():
            topic = f[5] | f[6] << 8
            if topic == SUBSCRIBER_INFO and b"drone_ros/ServoCommand" in f:
                return f[7] | f[8] << 8, k + 1
    raise AssertionError("the HA never announced its ServoCommand subscriber")


def qemu_cpu_s(pid):
    """User and system CPU seconds QEMU has used (proc(5): fields 14 and 15 of stat)."""
    with open("/proc/%d/stat" % pid) as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def loop_speed(image, steps=1000):
    """The PIL loop's pace as a flight sets it (no -icount): the HP's ServoCommand and the VN-200's
    bytes each period, the step record, the reply. Returns (steps/s, QEMU's CPU % of one core)."""
    rig = PilRig(image)
    try:
        k = 0
        for k in range(0, 50):
            rig.step(k)
        topic, k = negotiate(rig, k + 1)
        t0, cpu0 = time.monotonic(), qemu_cpu_s(rig.board.proc.pid)
        for seq in range(1, steps + 1):
            os.write(rig.host, frame(topic, servo_command(seq, -2.5)))
            rig.step(k + seq, wait_for=seq)
            rig.frames_from_ha()  # the HP reads what the HA sends, as the arduino node does
        wall, cpu = time.monotonic() - t0, qemu_cpu_s(rig.board.proc.pid) - cpu0
    finally:
        rig.close()
    return steps / wall, 100.0 * cpu / wall
