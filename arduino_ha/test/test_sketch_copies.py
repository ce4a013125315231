"""The Due sketch is assembled, not copied: arduino-cli compiles only inside the sketch folder, so
`make sketch-ha` (arduino_ha/tools/assemble_sketch.sh) puts the .ino, src/ and the one VN-200
protocol core (vn200_driver/core) together under .build/. No copy of that core is checked in, and
the assembled sketch holds every file its sources include, so the HA never flies a decoder the
host tests did not test."""
import pathlib
import re
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
HA = ROOT / "arduino_ha"
VN200_CORE = ROOT / "vn200_driver" / "core"
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def assemble(tmp_path):
    out = subprocess.run(["bash", str(HA / "tools" / "assemble_sketch.sh"), str(tmp_path)],
                         check=True, capture_output=True, text=True).stdout.strip()
    return pathlib.Path(out)


def test_no_copy_of_the_vn200_core_is_checked_in():
    assert not (HA / "src" / "vn200").exists(), "arduino_ha/src/vn200 is a copy: the sketch is assembled"


def test_the_assembled_sketch_carries_the_one_vn200_core_byte_for_byte(tmp_path):
    sketch = assemble(tmp_path)
    core = {p.name: p.read_bytes() for p in VN200_CORE.iterdir() if p.suffix in (".c", ".h")}
    copy = {p.name: p.read_bytes() for p in (sketch / "src" / "vn200").iterdir()}
    assert core and copy == core


def test_every_quoted_include_of_the_sketch_resolves_inside_the_assembled_sketch(tmp_path):
    sketch = assemble(tmp_path)
    assert (sketch / "arduino_ha.ino").is_file()
    missing = []
    sources = [sketch / "arduino_ha.ino"] + [p for p in (sketch / "src").rglob("*")
                                              if p.suffix in (".c", ".h", ".cpp")]
    for src in sources:
        for name in INCLUDE.findall(src.read_text(errors="replace")):
            # arduino-cli's include path: the including file's folder, then the sketch's root.
            if not ((src.parent / name).is_file() or (sketch / name).is_file()):
                missing.append("%s: %s" % (src.relative_to(sketch), name))
    assert not missing, missing


def test_decision_status_header_is_the_one_the_message_generates(tmp_path):
    """CONTROLLER_* and REASON_* are defined once, in msg/DecisionStatus.msg; the core's header
    is generated from it and must not drift."""
    fresh = tmp_path / "ha_decision_status.h"
    subprocess.run([sys.executable, str(ROOT / "tools" / "gen_decision_status.py"), "--c",
                    str(ROOT / "msg" / "DecisionStatus.msg"), str(fresh)], check=True)
    checked_in = ROOT / "arduino_ha" / "src" / "core" / "ha_decision_status.h"
    assert checked_in.read_text() == fresh.read_text(), \
        "run `make due-sketch-msgs` and check in arduino_ha/src/core/ha_decision_status.h"
