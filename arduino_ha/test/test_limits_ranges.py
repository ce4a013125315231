"""The HA generator checks limits.yaml against aircraft/limits_ranges.yaml, the table
controller_DG808 and microhard_gs check the same keys with: a limit one of them refuses, the HA
refuses too, so no limit reaches the Due that the HP side would not fly."""
import pathlib
import subprocess
import sys

import yaml

ROOT = pathlib.Path(__file__).resolve().parents[2]
GENERATOR = ROOT / "tools" / "gen_aircraft_config.py"
LIMITS = ROOT / "aircraft" / "DG808" / "limits.yaml"


def generate(tmp_path, section, key, value):
    doc = yaml.safe_load(LIMITS.read_text())
    doc[section][key] = value
    path = tmp_path / "limits.yaml"
    path.write_text(yaml.safe_dump(doc))
    return subprocess.run([sys.executable, str(GENERATOR), str(path), "-"], capture_output=True, text=True)


def test_a_roll_limit_the_controller_refuses_is_refused_by_the_ha_generator(tmp_path):
    result = generate(tmp_path, "state", "roll_limit_deg", 120.0)
    assert result.returncode != 0
    assert "roll_limit_deg = 120 is above 89" in result.stderr


def test_every_range_of_the_table_is_enforced_at_its_bounds(tmp_path):
    from stack_tools import gen_limits_ranges
    for path, (low, high) in gen_limits_ranges.ranges().items():
        section, key = path.split("/")
        below = generate(tmp_path, section, key, low - 0.5)
        assert below.returncode != 0 and key in below.stderr, path
        if high is not None:
            above = generate(tmp_path, section, key, high + 0.5)
            assert above.returncode != 0 and key in above.stderr, path


def test_the_aircraft_limits_lie_inside_the_table(tmp_path):
    doc = yaml.safe_load(LIMITS.read_text())
    result = generate(tmp_path, "state", "roll_limit_deg", doc["state"]["roll_limit_deg"])
    assert result.returncode == 0, result.stderr
