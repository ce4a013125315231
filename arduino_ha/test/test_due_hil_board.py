"""The Due's HIL build (src/board_due/due_hil_board.h) run on the host: the sketch with
HA_DUE_HIL=1 linked against the Arduino shim with a fake native USB port
(verify/due_hil_host_run.cpp, built by verify/board_compile_check.sh), fed step records made by
the simulator's own encoders (hil/ha_channel.py's STEP layout, hil/ha_qemu.py's frame(), what the
QEMU board takes on its UART2) and read back with the simulator's decoders. What the core reads
each period must be the latest good record's; every period must be answered with its outputs; a
frame failing its CRC or its length must be counted and dropped, and the good record behind it
still applied."""
import pathlib
import subprocess

import pytest

from hil import ha_channel, record_bridge
from stack_testing.due_host import build_due_host_programs

ROOT = pathlib.Path(__file__).resolve().parents[2]

CIC = (1100, 1500, 1500, 1500, 1000)  # computer in command, sticks centred
PIC = (1300, 1900, 1200, 1600, 2000)  # the pilot's switch up, sticks away from centre
HA, MANUAL = 1, 4  # DecisionStatus.CONTROLLER_*
GOOD = ha_channel.RC_VALID | ha_channel.AIRSPEED_OK | ha_channel.BATTERY_OK


@pytest.fixture(scope="module")
def runner(tmp_path_factory):
    return build_due_host_programs(tmp_path_factory.mktemp("board")) / "due_hil_host_run"


def record(rc=CIC, flags=GOOD, airspeed_ftps=50.0, battery_v=12.4):
    """A step record as the simulator sends it in real time (ha_channel.HaChannel.send_inputs)."""
    return ha_channel.STEP.pack(ha_channel.MAGIC_STEP, ha_channel.VERSION, flags, 0, 0, 0, 0, *rc, 0,
                                airspeed_ftps, battery_v)


def usb(data):
    return "usb " + bytes(data).hex()


class Run:
    def __init__(self, stdout):
        self.periods = []
        self.runs = []  # the periods of each `run` of the script
        tx = b""
        for line in stdout.splitlines():
            f = line.split()
            if f[0] == "run":
                self.runs.append([])
            elif f[0] == "period":
                self.runs[-1].append(len(self.periods))
                self.periods.append({"t_us": int(f[1]), "rc": tuple(int(v) for v in f[2:7]),
                                     "rc_valid": int(f[7]), "airspeed": float(f[8]), "battery": float(f[9])})
            elif f[0] == "usb_tx":
                tx = bytes.fromhex(f[1]) if len(f) > 1 else b""
        reader = record_bridge.FrameReader()
        self.replies = []
        for body in reader.feed(tx):
            reply = ha_channel.decode_reply(body[:record_bridge.REPLY_LEN])
            self.replies.append((reply, record_bridge.TRAILER.unpack(body[record_bridge.REPLY_LEN:])))
        assert reader.bad == 0 and not reader.buf, "the board wrote something that is no reply frame"

    def dropped(self):
        return self.replies[-1][1][0]

    def of_run(self, k):
        """The periods of the script's k-th run."""
        return [self.periods[i] for i in self.runs[k]]

    def replies_of_run(self, k):
        """The replies that answered them (one a period while the host reads)."""
        return [self.replies[i] for i in self.runs[k]]


def run(runner, script):
    done = subprocess.run([str(runner)], input="\n".join(script) + "\n", capture_output=True, text=True,
                          timeout=60)
    assert done.returncode == 0, done.stderr
    return Run(done.stdout)


def test_what_the_core_reads_each_period_is_the_latest_step_record(runner):
    r = run(runner, [usb(record_bridge.frame(record(PIC, airspeed_ftps=55.5, battery_v=11.8))), "run 50",
                     usb(record_bridge.frame(record(CIC, flags=ha_channel.BATTERY_OK, airspeed_ftps=70.0,
                                              battery_v=10.5))), "run 50"])
    first, second = r.of_run(0), r.of_run(1)
    assert len(first) == 6 and len(second) == 5  # the first period at once, then every 10 ms
    for p in first:
        assert (p["rc"], p["rc_valid"], p["battery"]) == (PIC, 1, pytest.approx(11.8, abs=1e-3))
        assert p["airspeed"] == pytest.approx(55.5, abs=1e-3)
    for p in second:  # RC lost and a failed AMS5812 read as the record says: the core gets -1
        assert (p["rc"], p["rc_valid"], p["battery"]) == (CIC, 0, pytest.approx(10.5, abs=1e-3))
        assert p["airspeed"] == -1.0


def test_each_period_is_answered_with_its_time_and_its_outputs(runner):
    r = run(runner, [usb(record_bridge.frame(record(CIC))), "run 300",
                     usb(record_bridge.frame(record(PIC))), "run 300"])
    assert len(r.replies) == len(r.periods) == 61
    for (reply, _), period in zip(r.replies, r.periods):
        assert reply.t_us == period["t_us"] and reply.flags & ha_channel.R_STEPPED
    # No HP on the link: the HA flies its own command, out to the servos.
    reply = r.replies[29][0]
    assert reply.controller == HA and reply.applied == pytest.approx(reply.ha_command)
    # The pilot's switch in the records gives the pilot the servos, his sticks, not the HA's command.
    reply = r.replies[-1][0]
    assert reply.controller == MANUAL
    assert reply.applied != pytest.approx(reply.ha_command)
    assert r.dropped() == 0


def test_a_frame_failing_its_crc_is_counted_and_dropped_and_the_good_record_behind_it_applied(runner):
    bad = bytearray(record_bridge.frame(record(PIC, airspeed_ftps=99.0)))
    bad[-2] ^= 0x10  # one bit of the CRC flipped on the way
    good = record_bridge.frame(record(CIC, airspeed_ftps=61.0))
    r = run(runner, [usb(record_bridge.frame(record(CIC))), "run 20", usb(bytes(bad) + good), "run 40"])
    assert r.dropped() == 1
    assert all(p["rc"] == CIC and p["airspeed"] != pytest.approx(99.0) for p in r.periods)
    assert r.periods[-1]["airspeed"] == pytest.approx(61.0, abs=1e-3)
    assert all(reply.controller != MANUAL for reply, _ in r.replies)


def test_frames_of_a_wrong_length_are_counted_and_dropped_and_the_good_record_behind_them_applied(runner):
    impossible = record_bridge.SYNC + b"\xff\x7f" + bytes(10)  # longer than any record
    short = record_bridge.frame(record(PIC, airspeed_ftps=99.0)[:40])  # framed and checked, no record
    good = record_bridge.frame(record(CIC, airspeed_ftps=61.0))
    r = run(runner, [usb(record_bridge.frame(record(CIC))), "run 20", usb(impossible + good), "run 20",
                     usb(short + record_bridge.frame(record(CIC, airspeed_ftps=62.0))), "run 20"])
    for k, (dropped, airspeed) in enumerate(((0, 50.0), (1, 61.0), (2, 62.0))):
        periods, replies = r.of_run(k), r.replies_of_run(k)
        assert [trailer[0] for _, trailer in replies] == [dropped] * len(replies)
        assert [p["airspeed"] for p in periods] == pytest.approx([airspeed] * len(periods))


def test_replies_no_host_reads_are_counted_as_dropped(runner):
    """A simulator that has the native port closed gets nothing; the next reply says how much."""
    frame_len = record_bridge.REPLY_LEN + record_bridge.TRAILER.size + 8
    r = run(runner, [usb(record_bridge.frame(record(CIC))), "close", "run 30", "open", "run 10"])
    closed, answered = r.of_run(0), r.of_run(1)
    assert len(closed) == 4 and len(answered) == 1 and len(r.replies) == 1
    assert r.replies[0][0].t_us == answered[0]["t_us"]
    assert r.replies[0][1][2] == len(closed) * frame_len


def test_a_reset_record_restarts_the_firmware_at_once_on_the_inputs_it_had(runner):
    """As a watchdog reset would: the schedule starts afresh (the first period at the next pass,
    not on the old 10 ms grid), and the pins still read what the simulator last sent."""
    reset = ha_channel.STEP.pack(ha_channel.MAGIC_RESET, ha_channel.VERSION, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
                                 0.0, 0.0)
    r = run(runner, [usb(record_bridge.frame(record(CIC, airspeed_ftps=55.0))), "run 25",
                     usb(record_bridge.frame(reset)), "run 12"])
    before, after = r.of_run(0), r.of_run(1)
    assert [p["t_us"] - before[0]["t_us"] for p in before] == [0, 9000, 19000]
    assert [p["t_us"] - before[-1]["t_us"] for p in after] == [6000, 16000]
    assert all(p["airspeed"] == pytest.approx(55.0) for p in after)
    assert len(r.replies) == 5 and r.dropped() == 0
