"""The Due sketch arduino-cli compiles is assembled under .build/ (`make sketch-ha`,
arduino_ha/tools/assemble_sketch.sh): arduino_ha's sources plus the ground floor from common/
(the geodesy, the HP command's CRC, the VN-200 protocol), which arduino-cli could not reach
outside the sketch folder. arduino-cli is not
installed here (test_due_image.py builds the folder against the real SAM core the way it does),
so these tests check what arduino-cli itself needs of the folder: every file the sketch includes
is inside it, found the way arduino-cli's compiler finds it (relative to the
including file; the sketch gets no include path of its own), and the VN-200 decoder in it is the
one the host tests test."""
import pathlib
import re
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
HA = ROOT / "arduino_ha"
VN200_CORE = ROOT / "common" / "vn200"
FLOOR = [ROOT / "common" / "src" / name for name in
         ("geo_wgs84.c", "geo_wgs84.h", "hp_command.c", "hp_command.h")]
LINK_MSGS = ROOT / "common" / "link" / "ha_link_msgs.h"
ASSEMBLE = HA / "tools" / "assemble_sketch.sh"
SOURCE_SUFFIXES = (".ino", ".c", ".cpp", ".h")
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]', re.M)
# What the Arduino SAM platform and its toolchain provide: the core, the two libraries the sketch
# installs (README.md) and the C/C++ standard headers the sources use.
PLATFORM_HEADERS = {"Arduino.h", "Servo.h", "Wire.h", "float.h", "math.h", "stdbool.h",
                    "stddef.h", "stdint.h", "string.h"}


def assemble(out):
    done = subprocess.run(["bash", str(ASSEMBLE), str(out)], check=True, capture_output=True,
                          text=True)
    return pathlib.Path(done.stdout.strip())


def sources(folder):
    return sorted(p for p in folder.rglob("*") if p.suffix in SOURCE_SUFFIXES)


def unresolved_includes(sketch):
    """Every #include of every sketch source that arduino-cli's compile would not find."""
    missing = []
    for source in sources(sketch):
        for kind, name in INCLUDE.findall(source.read_text(errors="replace")):
            if kind == "<":
                if name not in PLATFORM_HEADERS:
                    missing.append("%s: <%s> is not a platform header" % (source, name))
                continue
            target = (source.parent / name).resolve()
            if not target.is_file():
                missing.append("%s: \"%s\" not found" % (source, name))
            elif sketch.resolve() not in target.parents:
                missing.append("%s: \"%s\" lies outside the sketch folder" % (source, name))
    return missing


def test_assembled_sketch_is_a_folder_arduino_cli_accepts(tmp_path):
    sketch = assemble(tmp_path)
    assert sketch.name == "arduino_ha"
    assert (sketch / "arduino_ha.ino").is_file(), "the primary .ino must be named as its folder"


def test_every_file_the_assembled_sketch_includes_is_inside_it(tmp_path):
    sketch = assemble(tmp_path)
    assert unresolved_includes(sketch) == []


def test_the_source_tree_alone_lacks_the_vn200_core_the_assembly_adds():
    """The check above can fail: without the assembly, the INS seam's VN-200 headers are missing."""
    missing = unresolved_includes(HA)
    assert any("vn_binary.h" in m for m in missing), missing


def test_the_sketch_flies_the_vn200_core_the_host_tests_test(tmp_path):
    sketch = assemble(tmp_path)
    core = {p.name: p.read_bytes() for p in VN200_CORE.iterdir() if p.suffix in (".c", ".h")}
    in_sketch = {p.name: p.read_bytes() for p in (sketch / "src" / "vn200").iterdir()}
    assert core, "common/vn200 has no sources"
    assert {name: in_sketch.get(name) for name in core} == core


def test_the_sketch_runs_the_core_on_the_ground_floor_the_host_tests_test(tmp_path):
    """The geodesy and the HP command's CRC the Due compiles are common/src's, byte for byte, once:
    other folders reach them through a one-line header."""
    sketch = assemble(tmp_path)
    floor = {p.name: p.read_bytes() for p in FLOOR}
    in_core = {name: (sketch / "src" / "core" / name).read_bytes() for name in floor}
    assert in_core == floor
    compiled = sorted(str(p.relative_to(sketch)) for p in sketch.rglob("*.c") if p.name in floor)
    assert compiled == ["src/core/geo_wgs84.c", "src/core/hp_command.c"]
    forwarders = sorted(p for p in (sketch / "src").rglob("hp_command.h") if p.parent.name != "core")
    assert [p.parent.name for p in forwarders] == ["firmware", "hil", "link"]  # firmware: the retained record's CRC
    assert all(len(p.read_text().splitlines()) == 2 for p in forwarders)


def test_the_sketch_carries_the_message_code_msg_generates(tmp_path):
    """The link's message code is generated into the sketch from msg/, by the generator the host
    builds use: what the Due serializes is what the md5sums pinned in test/ describe."""
    sketch = assemble(tmp_path)
    assert (sketch / "src" / "link" / LINK_MSGS.name).read_bytes() == LINK_MSGS.read_bytes()
    gen = sketch / "src" / "link" / "generated"
    assert sorted(p.name for p in gen.iterdir()) == ["ha_msg_runtime.h", "ha_msgs.c", "ha_msgs.h"]
    header = (gen / "ha_msgs.h").read_text()
    pinned = dict(line.split() for line in (ROOT / "test" / "message_md5sums.txt").read_text().splitlines()
                  if line.startswith("drone_ros/"))
    found = {}
    for name, md5 in pinned.items():
        define = "#define DRONE_ROS_%s_MD5 " % name.split("/")[1].upper()
        for line in header.splitlines():
            if line.startswith(define):
                found[name] = line[len(define):].strip().strip('"')
    assert {"drone_ros/pwm", "drone_ros/DecisionStatus", "drone_ros/ServoCommand"} <= set(found), found
    assert found == {name: pinned[name] for name in found}


def test_no_generated_message_code_is_checked_in_under_arduino_ha():
    names = {"ha_msgs.h", "ha_msgs.c", "ha_msg_runtime.h"}
    copies = [str(p) for p in (HA / "src").rglob("*") if p.name in names]
    assert copies == [], "the sketch gets the message code at assembly (assemble_sketch.sh)"


def test_no_ground_floor_file_is_checked_in_under_arduino_ha():
    names = {p.name for p in VN200_CORE.iterdir() if p.suffix in (".c", ".h")} | {p.name for p in FLOOR} \
        | {LINK_MSGS.name}
    copies = [str(p) for p in HA.rglob("*") if p.name in names]
    assert copies == [], "common/ is the one source; the sketch gets it at assembly"


def assert_generated_from_message(tmp_path, mode, message, header):
    """The checked-in src/generated/<header> is what gen_decision_status.py <mode> writes from
    msg/<message> (arduino-cli runs no generator)."""
    fresh = tmp_path / header
    subprocess.run([sys.executable, str(ROOT / "tools" / "gen_decision_status.py"), mode,
                    str(ROOT / "msg" / message), str(fresh)], check=True)
    checked_in = HA / "src" / "generated" / header
    assert checked_in.read_text() == fresh.read_text(), \
        "run `make due-sketch-msgs` and check in arduino_ha/src/generated/%s" % header


def test_decision_status_header_is_the_one_the_message_generates(tmp_path):
    """CONTROLLER_* and REASON_* are defined once, in msg/DecisionStatus.msg; the core's header
    is generated from it and must not drift."""
    assert_generated_from_message(tmp_path, "--c", "DecisionStatus.msg", "ha_decision_status.h")


def test_operator_numbers_are_the_ones_the_message_generates(tmp_path):
    """HA_OP_* are defined once, in msg/OperatorCommand.msg, like the decision's numbers."""
    assert_generated_from_message(tmp_path, "--c-operator", "OperatorCommand.msg", "ha_operator_command.h")


def test_operator_numbers_that_collide_are_refused(tmp_path):
    msg = tmp_path / "OperatorCommand.msg"
    msg.write_text("uint8 SELECT_HP = 1\nuint8 SELECT_HA = 1\nuint8 command\n")
    done = subprocess.run([sys.executable, str(ROOT / "tools" / "gen_decision_status.py"), "--c-operator",
                           str(msg), str(tmp_path / "out.h")], capture_output=True, text=True)
    assert done.returncode == 1 and "distinct" in done.stderr
    assert not (tmp_path / "out.h").exists()
