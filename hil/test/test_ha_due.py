"""hil/ha_due.py, the simulator's end of a real Due, at its interfaces without a flight: the
control socket on one side, the Due's native port and its RX1 adapter (ptys here) on the other.
A record goes to the Due framed as its HIL board takes it; a reply comes back with its period
put on the host's clock; a reply frame that fails its CRC is counted and dropped, never passed
on; the VN-200's bytes reach RX1 unchanged; stale bytes in the native port are not taken for a
reply. DueClock dates the Due's ticks through drift, jitter and both clocks' wrap."""
import os
import random
import socket
import threading
import time

from hil import ha_channel, ha_due, ptys, record_bridge
from stack_tools.paths import ROOT

DG808 = os.path.join(ROOT, "aircraft", "DG808")  # whose period (100 Hz) the image runs


def test_the_due_clock_dates_ticks_within_the_least_latency_through_drift_and_wrap():
    rng = random.Random(7)
    for drift_ppm in (-60.0, 0.0, 60.0):
        clock = record_bridge.HaClock()
        host0_us = 2 ** 32 - 5_000_000  # the host's clock wraps 5 s in; the Due's at 20 s
        due0_us = 2 ** 32 - 20_000_000
        last = None
        for k in range(30_000):  # 300 s of 10 ms periods
            due_us = (due0_us + k * 10_000) & 0xFFFFFFFF
            true_host_us = host0_us + k * 10_000 * (1.0 + drift_ppm * 1e-6)
            latency_us = rng.uniform(300.0, 3_000.0) if rng.random() > 0.05 else rng.uniform(3_000.0, 40_000.0)
            dated = clock.to_host(due_us, int(true_host_us + latency_us) & 0xFFFFFFFF)
            error_us = ((dated - int(true_host_us) + 2 ** 31) % 2 ** 32) - 2 ** 31
            if k > 0:  # the first tick has only its own latency to go by
                assert 0 <= error_us <= 3_100, (drift_ppm, k, error_us)
                assert ((dated - last) & 0xFFFFFFFF) < 2 ** 31, "dated ticks went backwards"
            last = dated


def test_replies_that_came_late_for_a_while_never_date_the_next_on_time_one_before_them():
    clock = record_bridge.HaClock()
    dated = [clock.to_host(k * 10_000, k * 10_000 + 30_000) for k in range(5)]  # the bridge starved
    dated += [clock.to_host(k * 10_000, k * 10_000 + 500) for k in range(5, 10)]  # on time again
    assert all(0 < b - a for a, b in zip(dated, dated[1:])), dated
    assert dated[-1] == 90_500  # and dated by the on-time latency from then on


class Rig:
    """ha_due's bridge between a socket pair (the simulator's end kept here) and three ptys
    (the Due's native port, its RX1 adapter, the simulator's VN-200 port 1), on a thread."""

    def __init__(self, stale=b""):
        self.sim, chan = socket.socketpair(socket.AF_UNIX, socket.SOCK_SEQPACKET)
        self.native_m, native_s = ptys.open_raw()
        self.ins_m, ins_s = ptys.open_raw()
        self.vn_m, vn_s = ptys.open_raw()
        os.write(self.native_m, stale)
        self.fds = [native_s, ins_s, vn_s, self.native_m, self.ins_m, self.vn_m]
        native = ha_due.open_serial(os.ttyname(native_s), os.O_RDWR)
        ins = ha_due.open_serial(os.ttyname(ins_s), os.O_WRONLY)
        vn = ha_due.open_serial(os.ttyname(vn_s), os.O_RDONLY)
        self.fds += [native, ins, vn]
        self.bridge = record_bridge.RecordBridge(chan, native, ins, vn)
        self.stop = {"now": False}
        self.code = None
        self.thread = threading.Thread(target=self._run, daemon=True)
        self.thread.start()

    def _run(self):
        self.code = self.bridge.run(self.stop)

    def read(self, fd, n, timeout_s=5.0):
        got = b""
        deadline = time.monotonic() + timeout_s
        while len(got) < n and time.monotonic() < deadline:
            try:
                got += os.read(fd, n - len(got))
            except BlockingIOError:
                time.sleep(0.01)
        return got

    def close(self):
        self.stop["now"] = True
        self.sim.close()
        self.thread.join(timeout=5)
        for fd in self.fds:
            os.close(fd)
        self.bridge.chan.close()


def reply_frame(t_us, controller=2, tx_dropped=0, rx_dropped=0):
    body = ha_channel.REPLY.pack(ha_channel.MAGIC_REPLY, ha_channel.VERSION, ha_channel.R_STEPPED, t_us,
                                 *([0.0] * 8), controller, 0, 0, 0, 0, 0, 0, 0.0, 0.0, 0.0, 0, 0, 0, 0, 0)
    return record_bridge.frame(body + record_bridge.TRAILER.pack(0, 0, tx_dropped, rx_dropped))


def test_a_record_reaches_the_due_framed_and_its_reply_comes_back_on_the_hosts_clock():
    rig = Rig(stale=reply_frame(123, controller=3))  # what a reply of an earlier run left in the port
    try:
        record = ha_channel.STEP.pack(ha_channel.MAGIC_STEP, ha_channel.VERSION, ha_channel.RC_VALID, 0, 0, 0, 0,
                                      1100, 1500, 1500, 1500, 1000, 0, 50.0, 12.4)
        rig.sim.send(record)
        framed = record_bridge.frame(record)
        assert rig.read(rig.native_m, len(framed)) == framed
        rig.sim.settimeout(5.0)
        before_us = int(time.monotonic() * 1e6) & 0xFFFFFFFF
        os.write(rig.native_m, reply_frame(5_000_000))
        reply = ha_channel.decode_reply(rig.sim.recv(256))
        after_us = int(time.monotonic() * 1e6) & 0xFFFFFFFF
        # The stale reply never came: this is the Due's, dated on the host's clock at its arrival
        # (its first, so its latency is the clock's offset).
        assert reply.controller == 2
        assert ((reply.t_us - before_us) & 0xFFFFFFFF) <= ((after_us - before_us) & 0xFFFFFFFF)
        os.write(rig.native_m, reply_frame(5_010_000, tx_dropped=848, rx_dropped=3))
        assert ((ha_channel.decode_reply(rig.sim.recv(256)).t_us - reply.t_us) & 0xFFFFFFFF) <= 10_000
    finally:
        rig.close()
    assert rig.bridge.replies == 2 and rig.bridge.reader.bad == 0
    # The board's own drop counts, as its latest reply carried them, for the closing line.
    assert (rig.bridge.tx_dropped, rig.bridge.rx_dropped) == (848, 3)


def test_a_reply_frame_failing_its_crc_is_counted_and_dropped_and_the_next_passes():
    rig = Rig()
    try:
        bad = bytearray(reply_frame(1_000_000))
        bad[20] ^= 0x01
        os.write(rig.native_m, bytes(bad) + reply_frame(1_010_000, controller=1))
        rig.sim.settimeout(5.0)
        assert ha_channel.decode_reply(rig.sim.recv(256)).controller == 1
        rig.sim.settimeout(0.3)
        try:
            extra = rig.sim.recv(256)
        except socket.timeout:
            extra = None
        assert extra is None, "the damaged reply was passed on"
    finally:
        rig.close()
    assert rig.bridge.reader.bad == 1 and rig.bridge.replies == 1


def test_the_vn200s_bytes_reach_rx1_unchanged_and_the_simulator_closing_ends_the_bridge():
    rig = Rig()
    data = bytes(random.Random(3).randrange(256) for _ in range(3000))
    os.write(rig.vn_m, data)
    assert rig.read(rig.ins_m, len(data)) == data
    rig.sim.close()
    rig.thread.join(timeout=5)
    assert not rig.thread.is_alive() and rig.code == 0
    assert rig.bridge.ins_dropped == 0
    rig.stop["now"] = True
    for fd in rig.fds:
        os.close(fd)
    rig.bridge.chan.close()


def test_lockstep_is_refused_with_the_reason():
    assert ha_due.main(["--native", "/nonexistent", "--ins", "/nonexistent", "--vn200", "/nonexistent",
                        "--lockstep", "/nonexistent", "--aircraft-dir", DG808]) == 2


def test_a_rate_other_than_the_aircrafts_period_is_refused_with_it(capsys):
    assert ha_due.main(["--native", "/nonexistent", "--ins", "/nonexistent", "--vn200", "/nonexistent",
                        "--lockstep", "/nonexistent", "--aircraft-dir", DG808, "--realtime", "--rate-hz", "50"]) == 2
    assert "the image runs the aircraft's period (100 Hz" in capsys.readouterr().err
