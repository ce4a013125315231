"""Every YAML file the stack reads is checked against its schema (aircraft/schema/, by
tools/check_config.py) where it is read: a misspelt key (issue 27's state.stall_sped_ftps, which
used to pass the HA generator with exit 0 while the key it meant took no part) is refused with the
file and the key named, by the HA generator, the ranges and tunables generators, the HiL's airframe
and regions, the gain design, and by every launch file that loads the files into ROS parameters,
before any node starts."""
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
import yaml

ROOT = Path(__file__).resolve().parents[1]
AIRCRAFT = ROOT / "aircraft"
DG808 = AIRCRAFT / "DG808"
CHECK = ROOT / "tools" / "check_config.py"
from stack_tools import check_config  # noqa: E402


def misspell(path, key, typo):
    """Rename one key in place, as a typing slip does (comments and layout kept)."""
    text = path.read_text()
    pattern = re.compile(r"^(\s*(?:- )?)%s:" % re.escape(key), re.M)
    assert len(pattern.findall(text)) == 1, "%s: %s not found once" % (path.name, key)
    path.write_text(pattern.sub(r"\g<1>%s:" % typo, text))


def aircraft_copy(tmp_path):
    """A copy of the DG808's folder to break, named as the original (the readers go by names)."""
    folder = tmp_path / "DG808"
    shutil.copytree(DG808, folder)
    return folder


def run(cmd, **kw):
    return subprocess.run([str(c) for c in cmd], capture_output=True, text=True, timeout=120, **kw)


# One slip per kind of file: (file, key as written, the slip, the dotted path the error must name).
SLIPS = [
    ("limits.yaml", "stall_speed_ftps", "stall_sped_ftps", "state.stall_sped_ftps"),
    ("airframe.yaml", "ixz", "ixzz", "inertia_kg_m2.ixzz"),  # ixz silently defaulted to 0
    ("controller_param.yaml", "hmcmd", "hmcmdd", "hmcmdd"),
    ("ground_station.yaml", "max_retries", "max_retry", "mission.max_retry"),
    ("tunables.yaml", "tunables", "tunable", "tunable"),
    ("vn200_mount.yaml", "pitch_deg", "pich_deg", "pich_deg"),  # the mount silently level
]


def test_every_checked_in_aircraft_file_passes_its_schema():
    result = run([sys.executable, CHECK, AIRCRAFT])
    assert result.returncode == 0, result.stderr
    files = sorted(str(p.relative_to(ROOT)) for p in AIRCRAFT.rglob("*.yaml"))
    assert files and sorted(result.stdout.split()[1:]) == files


@pytest.mark.parametrize("name,key,typo,where", SLIPS, ids=[s[0] for s in SLIPS])
def test_a_misspelt_key_in_each_kind_of_file_is_refused_naming_it(tmp_path, name, key, typo, where):
    folder = aircraft_copy(tmp_path)
    misspell(folder / name, key, typo)
    result = run([sys.executable, CHECK, folder])
    assert result.returncode == 1
    assert "%s: %s: unknown key" % (folder / name, where) in result.stderr, result.stderr


def test_a_misspelt_range_in_limits_ranges_is_refused_naming_it(tmp_path):
    table = tmp_path / "limits_ranges.yaml"
    shutil.copy(AIRCRAFT / "limits_ranges.yaml", table)
    misspell(table, "stall_speed_ftps", "stall_sped_ftps")
    result = run([sys.executable, ROOT / "tools" / "gen_limits_ranges.py", table, tmp_path / "out.h"])
    assert result.returncode == 1
    assert "state.stall_sped_ftps: unknown key (did you mean stall_speed_ftps?)" in result.stderr
    assert not (tmp_path / "out.h").exists()


@pytest.mark.parametrize("beside", [False, True], ids=["instead", "beside_the_right_one"])
def test_the_issues_stall_sped_typo_stops_the_ha_generator_naming_the_key(tmp_path, beside):
    # Beside the right key it used to pass with exit 0; instead of it, the generator said only
    # "missing key: stall_speed_ftps".
    folder = aircraft_copy(tmp_path)
    limits = folder / "limits.yaml"
    if beside:
        limits.write_text(limits.read_text().replace("  stall_speed_ftps:", "  stall_sped_ftps: 38.0\n  stall_speed_ftps:"))
    else:
        misspell(limits, "stall_speed_ftps", "stall_sped_ftps")
    result = run([sys.executable, ROOT / "tools" / "gen_aircraft_config.py",
                  folder / "limits.yaml", "-"])
    assert result.returncode == 1
    assert "state.stall_sped_ftps: unknown key (did you mean stall_speed_ftps?)" in result.stderr
    assert result.stdout == ""


def test_the_hil_regions_refuse_a_misspelt_limits_key():
    # The simulator's and the verdicts' S_x and S_u come from the HA generator's build().
    from hil import verdicts
    doc = yaml.safe_load((DG808 / "limits.yaml").read_text())
    doc["sensors"]["max_wind_ftp"] = doc["sensors"]["max_wind_ftps"]
    with pytest.raises(Exception, match=r"sensors\.max_wind_ftp: unknown key"):
        verdicts.Regions(doc)


def test_the_build_refuses_a_misspelt_controller_parameter_naming_it(tmp_path):
    folder = aircraft_copy(tmp_path)
    misspell(folder / "controller_param.yaml", "hmcmd", "hmcmdd")
    result = run([sys.executable, ROOT / "tools" / "gen_tunables.py", folder / "tunables.yaml",
                  folder / "controller_param.yaml", tmp_path / "tunables_table.h"])
    assert result.returncode == 1
    assert "hmcmdd: unknown key (did you mean hmcmd?)" in result.stderr
    assert "hmcmd: missing" in result.stderr


def test_the_hil_airframe_refuses_a_misspelt_key_it_used_to_default(tmp_path):
    from hil.fdm.airframe import Airframe
    folder = aircraft_copy(tmp_path)
    Airframe(str(folder))  # the copy itself is good
    misspell(folder / "airframe.yaml", "ixz", "ixzz")
    with pytest.raises(ValueError, match=r"airframe\.yaml: inertia_kg_m2\.ixzz: unknown key"):
        Airframe(str(folder))


def test_the_gain_design_refuses_a_misspelt_airframe_key(tmp_path):
    # The design is a script (drone_ros/gnc/design/design_gains.py aircraft/<name>), not a package.
    folder = aircraft_copy(tmp_path)
    misspell(folder / "airframe.yaml", "cl_alpha_per_rad", "cl_alpha_per_radian")
    load = ("import sys, airframe_model\ntry:\n    airframe_model.load_airframe(sys.argv[1])\n"
            "except ValueError as error:\n    sys.exit('refused: %s' % error)")
    result = subprocess.run([sys.executable, "-c", load, str(folder / "airframe.yaml")],
                            cwd=ROOT / "drone_ros" / "gnc" / "design", capture_output=True, text=True)
    assert result.returncode == 1
    assert re.search(r"^refused: .*aero\.cl_alpha_per_radian: unknown key", result.stderr, re.M), result.stderr


def test_a_key_given_twice_is_refused_with_both_lines(tmp_path):
    # YAML keeps the last of two silently: an edit to the first would change nothing.
    path = tmp_path / "limits.yaml"
    text = (DG808 / "limits.yaml").read_text()
    path.write_text(text.replace("  ceiling_agl_ft:", "  ceiling_agl_ft: 300.0\n  ceiling_agl_ft:", 1))
    with pytest.raises(check_config.ConfigError, match=r"key 'ceiling_agl_ft' given twice \(first on line \d+\)"):
        check_config.load(str(path))


def test_a_value_of_the_wrong_type_is_refused_naming_the_key(tmp_path):
    path = tmp_path / "ground_station.yaml"
    path.write_text((DG808 / "ground_station.yaml").read_text().replace(
        "telemetry_rate_hz: 10.0", "telemetry_rate_hz: ten"))
    with pytest.raises(check_config.ConfigError, match=r"telemetry_rate_hz: 'ten' is not of type 'number'"):
        check_config.load(str(path))


def test_a_ground_station_file_that_still_names_a_home_is_refused(tmp_path):
    # The stack's one home is the HA's (/home); the old bench-only fixed home of the ground station
    # was a second one, about which /way could have been built.
    path = tmp_path / "ground_station.yaml"
    path.write_text((DG808 / "ground_station.yaml").read_text() + "\nhome:\n  fixed: true\n  lat_deg: 40.0\n"
                    "  lon_deg: -83.0\n  alt_m: 250.0\n")
    with pytest.raises(check_config.ConfigError, match=r"home"):
        check_config.load(str(path))


def test_a_misnamed_file_in_an_aircraft_folder_is_refused_not_ignored(tmp_path):
    folder = aircraft_copy(tmp_path)
    shutil.copy(folder / "limits.yaml", folder / "limit.yaml")
    result = run([sys.executable, CHECK, folder])
    assert result.returncode == 1 and "limit.yaml: no schema for a file of this name" in result.stderr


# The launch files: roslaunch runs the check while it reads them, before any node starts.

def launch_files():
    return sorted(p for p in ROOT.rglob("*.launch") if ".build" not in p.parts and ".venv" not in p.parts)


def loads_aircraft_yaml(element):
    return element.tag == "rosparam" and "/aircraft/" in element.get("file", "")


def test_every_launch_file_that_loads_aircraft_yaml_checks_it_first():
    loaders = []
    for path in launch_files():
        elements = list(ET.parse(path).getroot().iter())
        loads = [i for i, e in enumerate(elements) if loads_aircraft_yaml(e)]
        if not loads:
            continue
        loaders.append(path.name)
        checks = [i for i, e in enumerate(elements)
                  if e.tag == "include" and e.get("file", "").endswith("/launch/check_config.launch")]
        assert checks and checks[0] < loads[0], "%s loads aircraft YAML without checking it first" % path
    assert {"flight.launch", "microhard_gs.launch", "view.launch"} <= set(loaders)


@pytest.fixture
def package_copy(tmp_path):
    """This package with a copy of aircraft/ to break: every other top-level entry a link."""
    pkg = tmp_path / "src" / "drone_ros"
    pkg.mkdir(parents=True)
    tracked = run(["git", "ls-files"], cwd=ROOT).stdout.split()
    for entry in sorted({t.split("/")[0] for t in tracked}):
        if entry == "aircraft":
            shutil.copytree(AIRCRAFT, pkg / entry)
        else:
            (pkg / entry).symlink_to(ROOT / entry)
    # Only the copy: the workspace's devel space would point roslaunch at the original as well.
    prefixes = [p for p in os.environ.get("CMAKE_PREFIX_PATH", "").split(":")
                if p and not os.path.isfile(os.path.join(p, ".catkin"))]
    env = dict(os.environ, ROS_PACKAGE_PATH=str(pkg.parent), CMAKE_PREFIX_PATH=":".join(prefixes),
               ROS_HOME=str(tmp_path / "ros"), ROS_LOG_DIR=str(tmp_path / "log"))
    return pkg, env


def dump_params(env, launch, *args):
    return run(["roslaunch", "--dump-params", "drone_ros", launch] + list(args), env=env)


def test_the_hil_launch_passes_and_records_what_it_checked(package_copy):
    _, env = package_copy
    result = dump_params(env, "DG808_hil.launch")
    assert result.returncode == 0, result.stderr
    params = yaml.safe_load(result.stdout)
    assert "aircraft/DG808/limits.yaml" in params["/config_checked"]


@pytest.mark.parametrize("launch,name,key,typo,where", [
    ("DG808_hil.launch", "limits.yaml", "stall_speed_ftps", "stall_sped_ftps", "state.stall_sped_ftps"),
    ("DG808_flight.launch", "ground_station.yaml", "max_retries", "max_retry", "mission.max_retry"),
    ("DG808_flight.launch", "controller_param.yaml", "max_bank_deg", "max_bank_degs", "max_bank_degs"),
    ("DG808_flight.launch", "vn200_mount.yaml", "pitch_deg", "pich_deg", "pich_deg"),
])
def test_a_misspelt_key_fails_the_launch_files_before_any_node(package_copy, launch, name, key, typo, where):
    pkg, env = package_copy
    misspell(pkg / "aircraft" / "DG808" / name, key, typo)
    result = dump_params(env, launch)
    # roslaunch's --dump-params reports a load error but exits 0: no parameters is the failure.
    assert result.stdout.strip() == ""
    assert "aircraft/DG808/%s: %s: unknown key" % (name, where) in result.stderr, result.stderr
    assert "Cannot load command parameter [config_checked]" in result.stderr


def test_roslaunch_with_a_misspelt_key_exits_without_starting_anything(package_copy, tmp_path):
    pkg, env = package_copy
    misspell(pkg / "aircraft" / "DG808" / "limits.yaml", "ceiling_agl_ft", "ceiling_ft")
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    env = dict(env, ROS_MASTER_URI="http://127.0.0.1:%d" % port, ROS_IP="127.0.0.1")
    env.pop("ROS_HOSTNAME", None)
    launch = subprocess.Popen(["roslaunch", "drone_ros", "view.launch"], env=env, stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, text=True, start_new_session=True)
    try:
        _, err = launch.communicate(timeout=60)
    finally:
        if launch.poll() is None:  # it started something: stop all of it
            os.killpg(launch.pid, signal.SIGINT)
            launch.wait(timeout=30)
    assert launch.returncode == 1
    assert "state.ceiling_ft: unknown key (did you mean ceiling_agl_ft?)" in err
    assert not list((tmp_path / "log").rglob("master.log"))  # no roscore was started
