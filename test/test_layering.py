"""The layering of the C and C++: common/ is the ground floor, and the components above it (the
HA firmware, the VN-200 driver, the ground station, the HP nodes, the GNC) build on it and never
on each other, but for the edges BUILDS_ON names. A component that wanted another's code would
include its header, by a relative path or by name through an include directory; both are checked
here over the production sources (tests, fuzz harnesses and benchmarks may hold both ends of a
link)."""
import pathlib
import re
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1]
COMMON = ROOT / "common"
# The HP nodes' own floor: C++ every HP node may use (the serial port), above common/.
HP_COMMON = ROOT / "drone_ros" / "common"
NOT_PRODUCTION = {"test", "tests", "fuzz", "bench", "verify"}
SUFFIXES = {".c", ".cpp", ".h", ".hpp", ".ino"}


def has_sources(folder):
    return any(p.suffix in SUFFIXES for p in folder.rglob("*"))


# Each component's folder; drone_ros/ holds several nodes, each its own component.
COMPONENTS = ([ROOT / "arduino_ha", ROOT / "vn200_driver", ROOT / "microhard_gs"]
              + sorted(p for p in (ROOT / "drone_ros").iterdir() if p.is_dir() and p != HP_COMMON
                       and has_sources(p)))
# The one component another may build on: the controller node is the GNC's ROS edge (the node
# fills the GNC's input from topics and publishes its output); the GNC knows nothing of it.
BUILDS_ON = {("drone_ros/controller", "drone_ros/gnc")}
# The crossings that remain, each with what removes it. The test fails on any other crossing, and
# on a listed one that is gone (then delete its line).
KNOWN_CROSSINGS = set()
INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"', re.M)


def sources(folder):
    for p in sorted(folder.rglob("*")):
        if p.suffix in SUFFIXES and not NOT_PRODUCTION & set(p.relative_to(folder).parts[:-1]):
            yield p


def headers(folder):
    return {p.name for p in sources(folder) if p.suffix in (".h", ".hpp")}


def includes(path):
    return INCLUDE.findall(path.read_text(errors="replace"))


def test_every_component_has_sources_to_check():
    assert all(any(sources(c)) for c in COMPONENTS), [str(c) for c in COMPONENTS if not any(sources(c))]


def test_no_relative_include_leaves_its_component():
    leaks = []
    for component in COMPONENTS + [COMMON, HP_COMMON]:
        for src in sources(component):
            for name in includes(src):
                target = (src.parent / name).resolve()
                if ".." in name and target.is_file() and component.resolve() not in target.parents:
                    leaks.append("%s: %s" % (src.relative_to(ROOT), name))
    assert leaks == []


def test_no_component_includes_another_components_header_by_name():
    owner = {}
    for component in COMPONENTS:
        for name in headers(component):
            owner.setdefault(name, set()).add(component)
    floor = headers(COMMON) | headers(HP_COMMON)
    crossings = set()
    for component in COMPONENTS:
        for src in sources(component):
            for name in includes(src):
                base = pathlib.PurePosixPath(name).name
                if base in floor or (src.parent / name).is_file():
                    continue
                for other in owner.get(base, set()) - {component}:
                    crossings.add((str(component.relative_to(ROOT)), base, str(other.relative_to(ROOT))))
    assert {c for c in crossings if (c[0], c[2]) not in BUILDS_ON} == KNOWN_CROSSINGS
    # An edge no include takes any more is deleted from BUILDS_ON, not left to allow one later.
    assert BUILDS_ON <= {(c[0], c[2]) for c in crossings}


def test_the_floors_include_nothing_of_the_components_above_them():
    above = set().union(*(headers(c) for c in COMPONENTS))
    found = ["%s: %s" % (src.relative_to(ROOT), name) for floor in (COMMON, HP_COMMON)
             for src in sources(floor) for name in includes(src)
             if pathlib.PurePosixPath(name).name in above and not (src.parent / name).is_file()]
    assert found == []


@pytest.mark.parametrize("source", sorted(str(p.relative_to(ROOT)) for p in COMMON.rglob("*.c")))
def test_the_ground_floor_compiles_with_nothing_but_itself(source):
    """common/'s C needs no folder above it: only its own folders on the include path."""
    done = subprocess.run(["gcc", "-std=c99", "-pedantic", "-Wall", "-Wextra", "-Werror",
                           "-fsyntax-only", "-I", str(COMMON / "src"), "-I", str(COMMON / "vn200"),
                           str(ROOT / source)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
