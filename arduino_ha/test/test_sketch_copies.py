"""The Due sketch compiles a checked-in copy of the VN-200 protocol core (arduino_ha/src/vn200/,
made by `make due-sketch-vn200`), because arduino-cli only compiles inside the sketch folder.
These tests fail when that copy no longer matches vn200_driver/core, so the HA never flies a
decoder the host tests did not test."""
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
ORIGINAL = ROOT / "vn200_driver" / "core"
COPY = ROOT / "arduino_ha" / "src" / "vn200"
FIX = "run `make due-sketch-vn200` and check in arduino_ha/src/vn200/"


def sources(folder):
    return {p.name: p for p in folder.iterdir() if p.suffix in (".c", ".h")}


def test_sketch_has_every_vn200_core_file_and_no_other():
    original = sorted(sources(ORIGINAL))
    copy = sorted(sources(COPY))
    assert original, "vn200_driver/core has no sources"
    assert copy == original, FIX


def test_sketch_copy_of_vn200_core_is_byte_identical():
    copy = sources(COPY)
    differing = [name for name, path in sorted(sources(ORIGINAL).items())
                 if name in copy and copy[name].read_bytes() != path.read_bytes()]
    assert not differing, "%s differ; %s" % (", ".join(differing), FIX)


def test_decision_status_header_is_the_one_the_message_generates(tmp_path):
    """CONTROLLER_* and REASON_* are defined once, in msg/DecisionStatus.msg; the core's header
    is generated from it and must not drift."""
    fresh = tmp_path / "ha_decision_status.h"
    subprocess.run([sys.executable, str(ROOT / "tools" / "gen_decision_status.py"), "--c",
                    str(ROOT / "msg" / "DecisionStatus.msg"), str(fresh)], check=True)
    checked_in = ROOT / "arduino_ha" / "src" / "core" / "ha_decision_status.h"
    assert checked_in.read_text() == fresh.read_text(), \
        "run `make due-sketch-msgs` and check in arduino_ha/src/core/ha_decision_status.h"
