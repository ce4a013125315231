"""The HA switches on an inset of S_x, the ceiling and the stall speed (limits.yaml says why). The
generator refuses an inset that would make switching and handing back chatter, or one outside
S_x itself, naming the key."""
import pathlib
import subprocess
import sys

import pytest
import yaml

ROOT = pathlib.Path(__file__).resolve().parents[2]
GENERATOR = ROOT / "tools" / "gen_aircraft_config.py"
LIMITS = ROOT / "aircraft" / "DG808" / "limits.yaml"


def generate_from(tmp_path, doc):
    """The generator run on doc written out as limits.yaml."""
    path = tmp_path / "limits.yaml"
    path.write_text(yaml.safe_dump(doc))
    return subprocess.run([sys.executable, str(GENERATOR), str(path), "-"], capture_output=True, text=True)


def generate(tmp_path, **state):
    """The generator run on the DG808's limits with state's keys changed."""
    doc = yaml.safe_load(LIMITS.read_text())
    doc["state"].update(state)
    return generate_from(tmp_path, doc)


def test_the_switch_level_and_speed_reach_the_ha_derived_from_the_limits(tmp_path):
    r = generate(tmp_path)
    assert r.returncode == 0, r.stderr
    doc = yaml.safe_load(LIMITS.read_text())["state"]
    assert ".switch_region_fraction = %sf" % doc["switch_region_fraction"] in r.stdout
    assert ".ceiling_switch_agl_ft = %.1ff" % (doc["ceiling_agl_ft"] * doc["switch_region_fraction"]) in r.stdout


# An inset that would chatter (switching at or inside where the HA hands back) or that leaves S_x
# (a switch level past the region, a switch speed below stall): the state's keys, what is said.
REFUSED_INSETS = [
    ({"inner_region_fraction": 0.7, "switch_region_fraction": 0.7},
     "switch_region_fraction must exceed inner_region_fraction"),
    ({"switch_region_fraction": 1.05}, "switch_region_fraction"),
    ({"handback_stall_multiple": 1.2, "stall_switch_multiple": 1.2},
     "stall_switch_multiple must lie below handback_stall_multiple"),
    ({"stall_switch_multiple": 0.95}, "stall_switch_multiple"),
]


@pytest.mark.parametrize("state,said", REFUSED_INSETS, ids=[
    "switch_level_inside_the_hand_back_region", "switch_level_outside_s_x",
    "stall_switch_speed_at_the_hand_back_speed", "stall_switch_speed_below_stall"])
def test_an_inset_that_would_chatter_or_leave_s_x_is_refused_naming_the_key(tmp_path, state, said):
    r = generate(tmp_path, **state)
    assert r.returncode != 0
    assert said in r.stderr


def test_a_wind_that_would_excuse_a_stalled_pitot_is_refused(tmp_path):
    doc = yaml.safe_load(LIMITS.read_text())
    doc["sensors"]["max_wind_ftps"] = doc["state"]["stall_speed_ftps"] + 5.0
    r = generate_from(tmp_path, doc)
    assert r.returncode != 0 and "max_wind_ftps" in r.stderr
