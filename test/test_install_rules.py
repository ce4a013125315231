"""The install space flies without the source tree (issue 27): every file a launch file names as
$(find drone_ros)/<path> must be installed to share/drone_ros/<path> by an install() rule in the
CMake files, since in an install $(find drone_ros) is share/drone_ros. Read from the CMake and
launch files alone (no build): a launch folder, an aircraft file or the config checker that no
rule installs fails here, naming the launch file and the path. `make check-install` is the slow
proof: it builds an install space and resolves the flight launch from it."""
import re
import subprocess
from pathlib import Path, PurePosixPath

ROOT = Path(__file__).resolve().parents[1]
SHARE = "${CATKIN_PACKAGE_SHARE_DESTINATION}"
FIND = re.compile(r"\$\(find drone_ros\)/((?:\$\([^)]*\)|[^\"'\s<>$])+)")
INSTALL = re.compile(r"\binstall\s*\(([^()]*)\)", re.S)


def tracked(pattern):
    out = subprocess.run(["git", "ls-files", pattern], cwd=ROOT, check=True,
                         capture_output=True, text=True).stdout.split()
    return [ROOT / p for p in out]


def aircraft_names():
    return sorted(p.parent.name for p in (ROOT / "aircraft").glob("*/limits.yaml"))


def launch_files():
    """The launch files a user starts or includes (the tests' own are not installed)."""
    return [p for p in tracked("*.launch") if "test" not in p.relative_to(ROOT).parts]


def referenced_paths(launch):
    """The repository paths launch names through $(find drone_ros), with $(arg aircraft) taken
    for each aircraft folder; a path with another substitution is cut before it (its folder)."""
    text = re.sub(r"<!--.*?-->", "", launch.read_text(), flags=re.S)  # examples in comments
    out = set()
    for raw in FIND.findall(text):
        for name in aircraft_names():
            path = raw.replace("$(arg aircraft)", name)
            if "$(" in path:
                path = path[:path.index("$(")].rsplit("/", 1)[0]
            out.add(path.rstrip("/"))
    return out


def _relative_source(cmake_dir, token):
    token = token.replace("${PROJECT_SOURCE_DIR}", str(ROOT))
    token = token.replace("${CMAKE_CURRENT_SOURCE_DIR}", str(cmake_dir))
    path = Path(token) if Path(token).is_absolute() else cmake_dir / token
    return path.resolve()


class Rule:
    """One install() of files or a directory into the package's share folder."""

    def __init__(self, cmake_file, kind, sources, destination, excluded):
        self.cmake_file, self.kind, self.excluded = cmake_file, kind, excluded
        # A folder named with a trailing slash installs its contents, not itself.
        self.contents_only = {_relative_source(cmake_file.parent, s) for s in sources if s.endswith("/")}
        self.sources = [_relative_source(cmake_file.parent, s) for s in sources]
        self.destination = PurePosixPath(destination[len(SHARE):].lstrip("/"))

    def installed_as(self, source):
        """Where source (a repository file or folder) lands under share/drone_ros, or None."""
        for src in self.sources:
            if self.kind == "DIRECTORY":
                if source != src and src not in source.parents:
                    continue
                rest = source.relative_to(src).parts
                if any(part in self.excluded for part in rest):
                    return None
                top = () if src in self.contents_only else (src.name,)
                return self.destination.joinpath(*top, *rest)
            if source == src:
                return self.destination / src.name
        return None


def share_rules():
    rules = []
    for cmake_file in tracked("CMakeLists.txt") + tracked("*/CMakeLists.txt") + tracked("*/*/CMakeLists.txt"):
        text = re.sub(r"#[^\n]*", "", cmake_file.read_text())
        for body in INSTALL.findall(text):
            words = body.split()
            if not words or words[0] not in ("FILES", "PROGRAMS", "DIRECTORY") or "DESTINATION" not in words:
                continue
            at = words.index("DESTINATION")
            destination = words[at + 1].replace("${PROJECT_NAME}", "drone_ros")
            if not destination.startswith(SHARE):
                continue
            excluded = set()
            for i, word in enumerate(words):
                if word == "PATTERN" and i + 2 < len(words) and words[i + 2] == "EXCLUDE":
                    excluded.add(words[i + 1].strip('"'))
            rules.append(Rule(cmake_file, words[0], words[1:at], destination, excluded))
    return rules


def test_every_path_the_launch_files_find_is_installed_where_find_drone_ros_looks():
    rules = share_rules()
    checked, missing = 0, []
    for launch in launch_files():
        for path in sorted(referenced_paths(launch)):
            source = (ROOT / path).resolve()
            assert source.exists(), "%s names $(find drone_ros)/%s, which does not exist" % (
                launch.relative_to(ROOT), path)
            places = {r.installed_as(source) for r in rules} - {None}
            checked += 1
            if PurePosixPath(path) not in places:
                missing.append("%s: $(find drone_ros)/%s (installed as: %s)" % (
                    launch.relative_to(ROOT), path, ", ".join(map(str, places)) or "nothing"))
    assert checked > 10, "too few $(find drone_ros) paths found (%d): is the parser broken?" % checked
    assert not missing, "not installed to share/drone_ros/<path>:\n  " + "\n  ".join(missing)


def test_the_flight_launch_is_among_what_is_checked():
    """The parser finds what the flight launch needs (a guard that it reads the real files)."""
    flight = referenced_paths(ROOT / "launch" / "flight.launch")
    assert {"launch/check_config.launch", "aircraft/DG808/limits.yaml",
            "microhard_gs/launch/microhard_gs.launch"} <= flight
    check = referenced_paths(ROOT / "launch" / "check_config.launch")
    assert "tools/check_config.py" in check and "aircraft/DG808" in check


def test_a_launch_folder_left_out_of_the_install_is_reported():
    """The rule reader tells an installed folder from one left out (exclusions included)."""
    rules = share_rules()
    launch_dir = (ROOT / "launch").resolve()
    placed = {r.installed_as(launch_dir / "DG808_flight.launch") for r in rules} - {None}
    assert placed == {PurePosixPath("launch/DG808_flight.launch")}
    assert {r.installed_as(launch_dir / "test" / "test_launch_files.py") for r in rules} == {None}
    assert {r.installed_as((ROOT / "msg").resolve()) for r in rules} == {None}
    sim = {r.installed_as((ROOT / "hil" / "sim.py").resolve()) for r in rules} - {None}
    assert sim == set()  # the hil package is setup.py's: catkin_python_setup installs it, not share/
