"""make coverage-ha's report (arduino_ha/tools/coverage_report.py) on gcov JSON made up here: a
branch of a header counts once however many objects include it, taken if any object took it; a
file below its floor fails the target and names the file; every untaken branch is listed with its
source line."""
import gzip
import json
import os
import subprocess
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
REPORT = os.path.join(ROOT, "arduino_ha", "tools", "coverage_report.py")


def gcov_json(path, core, files):
    """files: {name: {line: [count per arc]}}"""
    doc = {"current_working_directory": core, "files": [
        {"file": name, "lines": [{"line_number": ln, "branches": [{"count": c, "throw": False} for c in counts]}
                                 for ln, counts in lines.items()]} for name, lines in files.items()]}
    with gzip.open(path, "wt") as f:
        json.dump(doc, f)
    return str(path)


def run(tmp_path, *args):
    core = tmp_path / "core"
    core.mkdir(exist_ok=True)
    (core / "rule.c").write_text("int a;\nif (x) {\n")
    (core / "num.h").write_text("static int n(int v) { return v ? 1 : 0; }\n")
    # Two objects include num.h: each takes one of its two arcs.
    a = gcov_json(tmp_path / "a.gcov.json.gz", str(core), {"rule.c": {2: [3, 0]}, "num.h": {1: [1, 0]}})
    b = gcov_json(tmp_path / "b.gcov.json.gz", str(core), {"num.h": {1: [0, 2]}, "/usr/include/x.h": {1: [0, 0]}})
    return subprocess.run([sys.executable, REPORT, "--core", str(core), *args, a, b],
                          capture_output=True, text=True)


def test_a_header_in_two_objects_counts_each_branch_once_and_files_outside_the_core_not_at_all(tmp_path):
    r = run(tmp_path)
    assert r.returncode == 0, r.stderr
    assert "metric: branch coverage num.h: 100.0 % (2 of 2)" in r.stdout
    assert "metric: branch coverage rule.c: 50.0 % (1 of 2)" in r.stdout
    assert "metric: branch coverage core: 75.0 % (3 of 4)" in r.stdout
    assert "x.h" not in r.stdout
    assert "rule.c:2 arc 1: if (x) {" in r.stdout  # the untaken one, with its source


def test_a_file_below_its_floor_or_the_core_below_its_own_fails_and_says_which(tmp_path):
    r = run(tmp_path, "--floor", "rule.c=100")
    assert r.returncode == 1
    assert "rule.c 50.0 % < 100.0 %" in r.stderr
    r = run(tmp_path, "--floor", "num.h=100", "--total-floor", "80")
    assert r.returncode == 1
    assert "core 75.0 % < 80.0 %" in r.stderr and "num.h" not in r.stderr
    assert run(tmp_path, "--floor", "num.h=100", "--total-floor", "75").returncode == 0
