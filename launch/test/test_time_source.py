"""Which clock the launch files put the nodes on (/use_sim_time, the master's one parameter for
it, as roslaunch sets it before any node starts): the flight on the wall clock, whatever a
lockstep HiL left on the same roscore; a lockstep HiL on the simulator's /clock; a real-time HiL
on the wall clock."""
import os
import subprocess

import pytest
import yaml

LAUNCH = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def dump_params(launch, *args):
    """The parameters roslaunch would set, without a master or a node."""
    out = subprocess.run(["roslaunch", "--dump-params", os.path.join(LAUNCH, launch)] + list(args),
                         capture_output=True, text=True, timeout=120)
    params = yaml.safe_load(out.stdout) if out.returncode == 0 else None
    assert isinstance(params, dict), out.stdout[-2000:] + out.stderr[-2000:]
    return params


def use_sim_time(launch, *args):
    return dump_params(launch, *args).get("/use_sim_time")


def test_the_flight_runs_on_the_wall_clock_even_on_a_master_a_lockstep_hil_left_on_sim_time():
    assert use_sim_time("DG808_flight.launch") is False


def test_two_aircraft_in_namespaces_set_the_masters_one_parameter_not_their_own():
    params = dump_params(os.path.join("test", "two_aircraft.launch"), "run_dir:=/nonexistent",
                         "gs_ports_uav1:=20001 20002", "gs_ports_uav2:=20003 20004")
    assert params.get("/use_sim_time") is False
    assert not [name for name in params if name.endswith("/use_sim_time") and name != "/use_sim_time"]


@pytest.mark.parametrize("mode,expected", [("lockstep", True), ("realtime", False)])
def test_a_hil_flight_runs_on_the_simulators_clock_only_in_lockstep(mode, expected):
    assert use_sim_time("DG808_hil.launch", "mode:=%s" % mode) is expected
