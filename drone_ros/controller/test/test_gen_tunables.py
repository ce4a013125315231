"""tools/gen_tunables.py: the aircraft's tunables list becomes the C++ table the controller and
microhard_gs share, and a list that drifts from controller_param.yaml (or breaks MAVLink's
16-character ids) stops the build with the reason."""
import os
import subprocess
import sys

import yaml

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..")
GEN = os.path.join(ROOT, "tools", "gen_tunables.py")
AIRCRAFT = os.path.join(ROOT, "aircraft", "DG808")


def generate(tmp_path, tunables):
    """Each entry with a range and units that fit DG808's controller_param.yaml unless it says
    otherwise, so that each test meets the error it is about."""
    entries = [dict({"range": [-1e6, 1e6], "units": "1"}, **t) for t in tunables]
    path = tmp_path / "tunables.yaml"
    path.write_text(yaml.safe_dump({"tunables": entries}))
    out = tmp_path / "tunables_table.h"
    run = subprocess.run([sys.executable, GEN, str(path), os.path.join(AIRCRAFT, "controller_param.yaml"), str(out)],
                         capture_output=True, text=True, timeout=60)
    return run, out


def test_the_aircrafts_list_becomes_a_table_of_every_entry(tmp_path):
    out = tmp_path / "tunables_table.h"
    run = subprocess.run([sys.executable, GEN, os.path.join(AIRCRAFT, "tunables.yaml"),
                          os.path.join(AIRCRAFT, "controller_param.yaml"), str(out)],
                         capture_output=True, text=True, timeout=60)
    assert run.returncode == 0, run.stderr
    text = out.read_text()
    with open(os.path.join(AIRCRAFT, "tunables.yaml")) as f:
        listed = yaml.safe_load(f)["tunables"]
    for t in listed:
        assert '{"%s", "%s", ' % (t["name"], t.get("mav_id", t["name"])) in text
    assert '{"guidance_selection", "GUIDANCE_SELECT", true, Apply::kGncRestart, nullptr, 0.0, 1.0, "1"}' in text
    assert '{"VTtrim", "VTtrim", false, Apply::kGncRestart, nullptr, 0.0, 300.0, "ft/s"}' in text


def test_a_name_the_controller_does_not_read_is_refused(tmp_path):
    run, out = generate(tmp_path, [{"name": "gamma_flag", "type": "integer", "apply": "gnc_restart"}])
    assert run.returncode != 0 and "gamma_flag" in run.stderr and "controller_param.yaml" in run.stderr
    assert not out.exists()


def test_a_long_name_needs_a_short_mavlink_id(tmp_path):
    run, _ = generate(tmp_path, [{"name": "min_airspeed_cmd_ftps", "type": "real", "apply": "gnc_restart"}])
    assert run.returncode != 0 and "16" in run.stderr


def test_a_fixed_entry_needs_its_reason(tmp_path):
    run, _ = generate(tmp_path, [{"name": "dt", "type": "real", "apply": "fixed"}])
    assert run.returncode != 0 and "why" in run.stderr


def test_a_range_that_leaves_out_the_parameter_files_value_is_refused(tmp_path):
    # controller_param.yaml flies VTtrim 60 ft/s.
    run, out = generate(tmp_path, [{"name": "VTtrim", "type": "real", "apply": "gnc_restart", "range": [70.0, 300.0]}])
    assert run.returncode != 0 and "VTtrim" in run.stderr and "outside its range" in run.stderr
    assert not out.exists()


def test_a_range_must_run_from_min_to_max(tmp_path):
    run, _ = generate(tmp_path, [{"name": "VTtrim", "type": "real", "apply": "gnc_restart", "range": [300.0, 0.0]}])
    assert run.returncode != 0 and "min below max" in run.stderr


def test_an_integers_range_is_whole(tmp_path):
    run, _ = generate(tmp_path, [{"name": "mpf_switch", "type": "integer", "apply": "gnc_restart", "range": [0, 1.5]}])
    assert run.returncode != 0 and "whole numbers" in run.stderr


def test_a_tunable_without_units_is_refused(tmp_path):
    path = tmp_path / "tunables.yaml"
    path.write_text(yaml.safe_dump({"tunables": [{"name": "VTtrim", "type": "real", "apply": "gnc_restart",
                                                  "range": [0.0, 300.0]}]}))
    run = subprocess.run([sys.executable, GEN, str(path), os.path.join(AIRCRAFT, "controller_param.yaml"),
                          str(tmp_path / "t.h")], capture_output=True, text=True, timeout=60)
    assert run.returncode != 0 and "units" in run.stderr
