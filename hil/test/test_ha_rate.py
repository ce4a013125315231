"""The HA's rate in the HiL is the aircraft's own (limits.yaml's decision.rate_hz, the period its
compiled-in configuration and the boards' images run) unless a run asks for another, as
make bench-hil does at 20 Hz: then the SIL and the simulator both get it, and the controller runs
at it too. Checked on what roslaunch would start (its --args and --dump-params, no master) and on
run_flight.py's roslaunch command."""
import os
import subprocess
import tempfile

import pytest
import yaml

from hil import run_flight
from hil.aircraft_period import decision_rate_hz
from stack_tools.paths import ROOT

HIL_LAUNCH = os.path.join(ROOT, "launch", "DG808_hil.launch")
DIRS = ["run_dir:=/nonexistent/run", "out_dir:=/nonexistent/out"]


def roslaunch(*argv):
    out = subprocess.run(["roslaunch"] + list(argv), capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stdout[-2000:] + out.stderr[-2000:]
    return out.stdout


def board_args(node, *launch_args):
    """The command line roslaunch would give node."""
    return roslaunch("--args", node, HIL_LAUNCH, *(DIRS + list(launch_args))).split()


def sim_rate_param(*launch_args):
    return yaml.safe_load(roslaunch("--dump-params", HIL_LAUNCH, *(DIRS + list(launch_args)))).get(
        "/hil_sim/rate_hz")


def flight_command(*argv):
    args, d = run_flight.parse_args(["--folder", os.path.join(tempfile.mkdtemp(prefix="ha_rate_"), "f")]
                                    + list(argv))
    return run_flight.launch_command(args, d, "/nonexistent/run", d.out, 20001, 20002)


def test_the_aircraft_decides_at_100_hz():
    assert decision_rate_hz(os.path.join(ROOT, "aircraft", "DG808")) == 100.0


def test_without_a_rate_the_sil_and_the_simulator_take_the_aircrafts_own():
    assert "--rate-hz" not in board_args("/ha_sil")
    assert sim_rate_param() is None


@pytest.mark.parametrize("rate", ["20", "20.5"])
def test_a_rate_asked_for_reaches_the_sil_and_the_simulator(rate):
    argv = board_args("/ha_sil", "rate_hz:=" + rate)
    assert argv[argv.index("--rate-hz") + 1] == rate
    assert sim_rate_param("rate_hz:=" + rate) == float(rate)


def test_a_rate_asked_of_the_due_is_passed_on_for_it_to_refuse():
    argv = board_args("/ha_due", "ha:=due", "mode:=realtime", "rate_hz:=50")
    assert argv[argv.index("--rate-hz") + 1] == "50"


def test_run_flight_leaves_the_ha_its_aircrafts_rate_and_steps_the_controller_at_it():
    cmd = flight_command()
    assert not [a for a in cmd if a.startswith("rate_hz:=")]
    assert "dt:=0.01" in cmd


def test_run_flight_at_20_hz_runs_the_ha_and_the_controller_at_20_hz():
    cmd = flight_command("--rate-hz", "20")
    assert "rate_hz:=20" in cmd and "dt:=0.05" in cmd
    cmd = flight_command("--rate-hz", "20", "--controller-hz", "10")
    assert "rate_hz:=20" in cmd and "dt:=0.1" in cmd


def test_an_aircraft_with_no_folder_is_left_to_the_launch_to_refuse():
    # run_flight.py does not fail first with a traceback of its own: roslaunch says which
    # aircraft is missing, and the run reports it (test_campaign's launch that fails).
    assert not [a for a in flight_command("--aircraft", "NO_SUCH_AIRCRAFT") if a.startswith("dt:=")]
