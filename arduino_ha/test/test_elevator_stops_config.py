"""The two elevator stops of limits.yaml come from airframe.yaml's pitching moment: the HA's own
pull (safety_controller.elevator_pull_max_deg) must trim the wing below its stall, and the HP's
pull limit (actuators.elevator_pull_limit_deg) must not be below the elevator that trims the
stall, or a healthy HP flying near it would be taken out. The generator refuses either, naming
the key and the angle it trims at."""
import pathlib
import subprocess
import sys

import yaml

ROOT = pathlib.Path(__file__).resolve().parents[2]
GENERATOR = ROOT / "tools" / "gen_aircraft_config.py"
LIMITS = ROOT / "aircraft" / "DG808" / "limits.yaml"


def generate(tmp_path, actuators=None, safety_controller=None):
    doc = yaml.safe_load(LIMITS.read_text())
    doc["actuators"].update(actuators or {})
    doc["safety_controller"].update(safety_controller or {})
    path = tmp_path / "limits.yaml"
    path.write_text(yaml.safe_dump(doc))
    return subprocess.run([sys.executable, str(GENERATOR), str(path), "-"], capture_output=True, text=True)


def test_the_dg808_stops_reach_the_ha():
    doc = yaml.safe_load(LIMITS.read_text())
    r = subprocess.run([sys.executable, str(GENERATOR), str(LIMITS), "-"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert ".elevator_pull_limit_deg = %sf" % doc["actuators"]["elevator_pull_limit_deg"] in r.stdout
    assert ".sc_elevator_pull_max_deg = %sf" % doc["safety_controller"]["elevator_pull_max_deg"] in r.stdout


def test_an_own_stop_that_trims_the_wing_at_its_stall_is_refused(tmp_path):
    # cm0 0.045, cm_alpha -0.9, cm_elevator -1.3: 4.5 deg of nose-up elevator trims at 9.36 deg,
    # past stall_alpha_deg 8.8.
    r = generate(tmp_path, safety_controller={"elevator_pull_max_deg": 4.5})
    assert r.returncode != 0
    assert "elevator_pull_max_deg = 4.5 trims the wing at 9.36 deg, at or past stall_alpha_deg 8.8" in r.stderr


def test_a_pull_limit_below_the_stall_trim_is_refused(tmp_path):
    r = generate(tmp_path, actuators={"elevator_pull_limit_deg": 3.0},
                 safety_controller={"elevator_pull_max_deg": 2.5})
    assert r.returncode != 0
    assert "elevator_pull_limit_deg = 3 trims the wing at 7.20 deg, below its 8.85 deg stall" in r.stderr


def test_an_own_stop_beyond_the_pull_limit_is_refused(tmp_path):
    r = generate(tmp_path, actuators={"elevator_pull_limit_deg": 5.0},
                 safety_controller={"elevator_pull_max_deg": 6.0})
    assert r.returncode != 0
    assert "elevator_pull_max_deg" in r.stderr
