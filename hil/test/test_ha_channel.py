"""The HA in the loop without ROS: driven over its control channel, its VN-200 port fed by the
simulator's sensor model, stepped on simulation time. Each story runs twice: on the host SIL
(ha_sil) and on the firmware as Cortex-M3 machine code in QEMU (hil/ha_qemu.py, processor in the
loop), which takes the same arguments and speaks the same records."""
import math
import os
import subprocess
import sys
import tempfile
import time

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
from hil import ha_channel, sensors  # noqa: E402
from stack_testing.ha_in_loop import Parked, build_pil_image  # noqa: E402


def ha_sil_path():
    ws = os.environ.get("DRONE_ROS_WS", os.path.join(ROOT, ".build", "ws"))
    path = os.path.join(ws, "devel", "lib", "drone_ros", "ha_sil")
    if not os.path.exists(path):
        pytest.fail("ha_sil is not built (%s): run make build" % path)
    return path


@pytest.fixture(scope="session")
def pil_image(tmp_path_factory):
    return build_pil_image(str(tmp_path_factory.mktemp("pil")))


@pytest.fixture(params=["sil", "qemu"])
def rig(request):
    d = tempfile.mkdtemp(prefix="ha_channel_")
    chan = ha_channel.HaChannel(os.path.join(d, "ctl"))
    vn = sensors.Vn200Port(os.path.join(d, "ha_vn200"), 1, seed=7, baud=sensors.HA_VN200_BAUD,
                           fixed_output=sensors.HA_OUTPUT_1)
    args = ["--port", os.path.join(d, "ha_link"), "--vn200", os.path.join(d, "ha_vn200"),
            "--lockstep", os.path.join(d, "ctl")]
    if request.param == "sil":
        argv = [ha_sil_path()] + args
    else:
        argv = [sys.executable, os.path.join(ROOT, "hil", "ha_qemu.py"), "--image",
                request.getfixturevalue("pil_image"), "--aircraft-dir",
                os.path.join(ROOT, "aircraft", "DG808")] + args
    proc = subprocess.Popen(argv, stderr=subprocess.PIPE)
    assert chan.accept(20.0), "the HA (%s) did not connect to the control channel" % request.param
    yield chan, vn, proc
    chan.close()
    proc.terminate()
    proc.wait(timeout=10)
    vn.close()


def step(chan, vn, k, truth, period_us=10000, airspeed=0.0):
    t_us = k * period_us
    vn.emit_until(t_us * 1e-6, lambda t: truth)
    return chan.step(t_us, vn.pty.written, None, 2000, (1100, 1500, 1500, 1500, 1000), True,
                     airspeed, 12.4)


def test_ha_steps_on_simulation_time_and_latches_home_from_its_own_vn200(rig):
    chan, vn, _ = rig
    first = step(chan, vn, 0, Parked)
    assert first.flags & ha_channel.R_STEPPED
    for k in range(1, 50):
        r = step(chan, vn, k, Parked)
    assert r.t_us == 49 * 10000
    assert r.vn_bytes_read == vn.pty.written  # every byte the sensor sent was taken this period
    assert r.ins_solutions_used > 0 and r.ins_bad_packets == 0
    assert r.flags & ha_channel.R_STATE_VALID
    assert r.controller == 1  # no HP: the HA flies
    assert all(math.isfinite(v) for v in r.applied + r.ha_command)
    assert r.applied[3] == pytest.approx(0.0)  # parked: the motor idles


def test_without_the_hp_the_ha_never_waits_and_without_an_ins_its_state_stays_invalid(rig):
    chan, _, _ = rig
    t0 = time.monotonic()
    for k in range(20):
        r = chan.step(k * 10000, 0, None, 2000, (1100, 1500, 1500, 1500, 1000), True, 60.0, 12.4)
    assert time.monotonic() - t0 < 20.0
    assert not r.flags & ha_channel.R_STATE_VALID
    assert r.controller == 1


def test_a_command_that_never_comes_is_waited_for_only_as_long_as_bounded(rig):
    chan, _, _ = rig
    r = chan.step(10000, 0, 12345, 50, (1100, 1500, 1500, 1500, 1000), True, 60.0, 12.4)
    assert r.flags & ha_channel.R_COMMAND_TIMEOUT
    assert r.commands_received == 0


def test_pilot_switch_from_the_simulated_receiver_gives_the_pilot_the_servos(rig):
    chan, vn, _ = rig
    for k in range(40):
        vn.emit_until(k * 0.01, lambda t: Parked)
        r = chan.step(k * 10000, vn.pty.written, None, 2000, (1500, 1800, 1500, 1500, 2000), True,
                      0.0, 12.4)
    assert r.controller == 4  # MANUAL
    assert r.applied[0] > 5.0  # the elevator stick at 1800 us


class Cruising(Parked):
    """200 ft above the field, 60 ft/s to the north-east."""
    alt_msl_m = Parked.alt_msl_m + 61.0
    vn_mps = ve_mps = 13.0


def test_a_reset_in_flight_keeps_home_and_the_airborne_latch(rig):
    """Issue 22, F5: the HA reset in flight (RAM afresh, as a watchdog reset does) comes back with
    its home and its airborne latch from the board's retained words: its state is valid at the
    first solution after the reset (home cannot latch in flight) and the motor keeps running."""
    chan, vn, _ = rig
    k = 0
    for k in range(k, 100):
        r = step(chan, vn, k, Parked)  # the pitot reads still air: home latches on the ground
    assert r.flags & ha_channel.R_HOME and r.flags & ha_channel.R_STATE_VALID
    for k in range(100, 400):
        r = step(chan, vn, k, Cruising, airspeed=60.0)
    assert r.applied[3] > 0.2  # flying: the HA's throttle loop holds the speed
    r = chan.reset()
    assert not r.flags & ha_channel.R_STEPPED
    assert r.flags & ha_channel.R_HOME  # taken back before the first period
    assert r.vn_bytes_read == vn.pty.written  # the SIL's byte count goes on (the simulator waits on it)
    for k in range(400, 410):
        r = step(chan, vn, k, Cruising, airspeed=60.0)
    assert r.flags & ha_channel.R_HOME and r.flags & ha_channel.R_STATE_VALID
    assert r.controller == 1  # the HA, no HP in this rig
    for k in range(410, 600):
        r = step(chan, vn, k, Cruising, airspeed=60.0)
    assert r.applied[3] > 0.2  # still airborne: not idled as on a power-up on the ground


def test_a_power_up_in_the_air_never_latches_home(rig):
    """Issue 22, K9: the first solution arrives in the air (a level leg into a headwind looks
    parked to the INS): no home, however long, while the pitot says flying; the HA keeps its
    attitude (the state is stamped) but no height."""
    chan, vn, _ = rig

    class IntoWind(Cruising):
        vn_mps = ve_mps = 6.0  # 28 ft/s over the ground: below the stall speed, level
    for k in range(500):
        r = step(chan, vn, k, IntoWind, airspeed=60.0)
    assert not r.flags & ha_channel.R_HOME
    assert r.flags & ha_channel.R_STATE_VALID
    assert r.ins_solutions_used > 0
