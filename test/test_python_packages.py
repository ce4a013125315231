"""The stack's Python is packages (setup.py, catkin_python_setup): with the workspace sourced,
`import hil.verdicts` works from any folder under both ROS's Python and the venv's, and no file
reaches another folder's modules by editing sys.path (issue 26: there were 106 such edits).
`make check-install` imports the same packages from an install space."""
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# The packages setup.py declares; hil.fdm needs jsbsim (PyPI, the venv), the rest ROS's Python.
PACKAGES = ["stack_tools.check_config", "stack_tools.gen_aircraft_config", "hil.verdicts",
            "hil.campaigns.plan", "hil.faults.base", "report_core.flight_log",
            "supervisor_core.node_query", "vn200_sim.vn200_emulation", "vn200_sim.vn200_encode",
            "stack_testing.wire_tap", "stack_common.geo", "stack_common.crc"]
EDIT = re.compile(r"sys\.path\s*(\.(insert|append|extend)\b|\[[^]]*\]\s*=|\+=|=)")


def python_files():
    out = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, check=True, capture_output=True).stdout
    for name in out.decode().split("\0"):
        path = os.path.join(ROOT, name)
        if not name or not os.path.isfile(path):
            continue
        if name.endswith(".py"):
            yield name, path
            continue
        with open(path, "rb") as f:
            if re.match(rb"#!.*python", f.readline()):
                yield name, path


def test_no_file_edits_sys_path():
    edits = []
    for name, path in python_files():
        with open(path, encoding="utf-8") as f:
            for n, line in enumerate(f, 1):
                if EDIT.search(line.split("#", 1)[0]):
                    edits.append("%s:%d: %s" % (name, n, line.strip()))
    assert edits == [], "import through a package of setup.py instead:\n" + "\n".join(edits)


def test_the_scan_knows_an_edit_when_it_sees_one():
    path = "sys" + ".path"  # spelt apart, or the scan above finds these lines
    for line in (path + ".insert(0, HERE)", path + ".append('x')", path + "[:0] = [d]", path + " += [d]"):
        assert EDIT.search(line), line
    assert not EDIT.search("print(%s)" % path)


def imports_from_root(python, modules):
    code = "import %s\nprint(hil.verdicts.__file__)" % ", ".join(modules)
    return subprocess.run([python, "-c", code], cwd="/", capture_output=True, text=True, timeout=60)


def test_the_packages_import_from_any_folder_in_ros_python():
    result = imports_from_root("/usr/bin/python3", PACKAGES)
    assert result.returncode == 0, result.stderr
    assert os.path.samefile(result.stdout.strip(), os.path.join(ROOT, "hil", "verdicts.py")), result.stdout


def test_the_packages_import_from_any_folder_in_the_venv():
    result = imports_from_root(sys.executable, PACKAGES + ["hil.fdm", "hil.sim", "stack_testing.gs_harness",
                                                           "stack_testing.fault_flight"])
    assert result.returncode == 0, result.stderr


def test_the_data_root_is_the_package_with_its_aircraft():
    from stack_tools.paths import ROOT as data_root
    assert os.path.isfile(os.path.join(data_root, "aircraft", "schema", "limits.schema.json"))
