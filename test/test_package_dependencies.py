"""package.xml declares what the code uses, so rosdep and a binary build install it: every CMake
find_package, C++ include, Python import, launch-file node and ROS command-line tool the tree
uses is mapped to its rosdep key (or, for the few packages only PyPI has, to a requirements.txt
line), and the key is declared for the time it is needed: to build, to run, or to test. A new
import or include that is not in the tables below fails here until it is mapped and declared."""
import ast
import os
import re
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SELF = "drone_ros"

# Python module (top-level name) -> rosdep key; "pypi:<name>": only on PyPI, in a requirements.txt.
PYTHON_MODULES = {
    "yaml": "python3-yaml", "jsonschema": "python3-jsonschema", "numpy": "python3-numpy",
    "scipy": "python3-scipy", "matplotlib": "python3-matplotlib", "distributed": "python3-distributed",
    "cloudpickle": "python3-cloudpickle", "pytest": "python3-pytest", "catkin_pkg": "python3-catkin-pkg",
    "setuptools": "python3-setuptools",
    "rospkg": "python3-rospkg", "rospy": "rospy", "rosbag": "rosbag", "rosgraph": "rosgraph",
    "rosparam": "rosparam", "roslib": "roslib", "rostest": "rostest", "genpy": "genpy", "genmsg": "genmsg",
    "roscpp": "roscpp", "roslaunch": "roslaunch",
    "std_msgs": "std_msgs", "sensor_msgs": "sensor_msgs", "geometry_msgs": "geometry_msgs",
    "diagnostic_msgs": "diagnostic_msgs", "rosgraph_msgs": "rosgraph_msgs", "tf2_msgs": "tf2_msgs",
    "visualization_msgs": "visualization_msgs", "nav_msgs": "nav_msgs",
    "pymavlink": "pypi:pymavlink", "jsbsim": "pypi:jsbsim", "xdist": "pypi:pytest-xdist",
}
# C++ include (first path component, or the file name) -> rosdep key; None: this package's own.
CPP_INCLUDES = {
    "ros": "roscpp", "std_msgs": "std_msgs", "sensor_msgs": "sensor_msgs", "geometry_msgs": "geometry_msgs",
    "diagnostic_msgs": "diagnostic_msgs", "diagnostic_updater": "diagnostic_updater", "tf2_ros": "tf2_ros",
    "topic_tools": "topic_tools", "xmlrpcpp": "xmlrpcpp", "XmlRpcValue.h": "xmlrpcpp", "boost": "boost",
    "Eigen": "eigen", "yaml-cpp": "yaml-cpp", "gtest": "gtest", "rosgraph_msgs": "rosgraph_msgs",
    "nav_msgs": "nav_msgs", SELF: None, "drone_ros_common": None,
    "development": "pypi:pymavlink",  # the MAVLink headers mavgen writes at build time
    # The Arduino core's (arduino-cli's, or arduino_ha/verify's shim of it): not built by catkin.
    "Arduino.h": None, "Wire.h": None, "Servo.h": None,
}
# CMake find_package name -> rosdep key (None: the system's, like Threads).
CMAKE_PACKAGES = {"Eigen3": "eigen", "yaml-cpp": "yaml-cpp", "Threads": None, "catkin": "catkin"}
# ROS command-line tools the code runs -> the package that installs them.
ROS_TOOLS = {"roscore": "roslaunch", "roslaunch": "roslaunch", "rosparam": "rosparam", "rosbag": "rosbag",
             "rosmaster": "rosmaster", "rostopic": "rostopic", "rosservice": "rosservice", "rosnode": "rosnode",
             "rosrun": "rosbash", "mavproxy.py": "pypi:MAVProxy"}
# Build-time Python: the generators CMake runs, and what they import from the tree. check_config also
# runs at launch (launch/check_config.launch), so its imports are run-time ones too.
BUILD_ONLY = re.compile(r"^(tools/gen_[a-z_]+\.py|tools/stack_tools/(gen_[a-z_]+|generated_file)\.py|setup\.py|"
                        r"arduino_ha/tools/[a-z_]+\.py|common/link/gen/[a-z_0-9]+\.py)$")
BUILD_AND_RUN = {"tools/check_config.py", "tools/stack_tools/check_config.py"}
# Declarations that serve each time.
KINDS = {"build": ("depend", "build_depend", "buildtool_depend"), "run": ("depend", "exec_depend"),
         "test": ("depend", "exec_depend", "test_depend"),
         "test_build": ("depend", "build_depend", "test_depend")}  # a C++ test: built with the package


def tracked():
    out = subprocess.run(["git", "ls-files"], cwd=ROOT, capture_output=True, text=True, check=True)
    return out.stdout.split()


def times(path):
    """When a file is used: to build, to run, to test."""
    parts = path.split("/")
    if any(p in ("test", "bench", "fuzz", "verify", "design") for p in parts[:-1]) or parts[-1].startswith("test_") \
            or parts[-1].endswith(".test") or parts[-1] == "conftest.py":  # pytest's own set-up file
        return {"test"}
    if path in BUILD_AND_RUN:
        return {"build", "run"}
    if BUILD_ONLY.match(path):
        return {"build"}
    return {"run"}


def python_files(files):
    for f in files:
        if f.endswith(".py"):
            yield f
        elif "." not in os.path.basename(f):
            with open(ROOT / f, "rb") as h:
                first = h.readline()
            if first.startswith(b"#!") and b"python" in first:
                yield f


def in_tree_modules(files):
    names = {SELF} | {part for f in files for part in f.split("/")[:-1]}  # packages, namespace ones too
    for f in files:
        if f.endswith(".py"):
            names.add(os.path.basename(f)[:-3])
        if f.endswith("/__init__.py"):
            names.add(f.split("/")[-2])
    return names


def python_uses(files):
    """(file, what, rosdep key) for every third-party import; unknown modules as key None."""
    local = in_tree_modules(files)
    for f in python_files(files):
        for node in ast.walk(ast.parse((ROOT / f).read_text(), f)):
            if isinstance(node, ast.Import):
                modules = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                modules = [node.module]
            else:
                continue
            for module in modules:
                top = module.split(".")[0]
                if top in sys.stdlib_module_names or top in local:
                    continue
                yield f, "import " + top, PYTHON_MODULES.get(top, "?")


SYSTEM_DIRS = {"sys", "netinet", "arpa", "asm", "linux"}
INCLUDE = re.compile(r'^\s*#\s*include\s*<([^>]+)>', re.M)


def cpp_uses(files):
    for f in files:
        if not f.endswith((".c", ".cpp", ".h", ".hpp")):
            continue
        for header in INCLUDE.findall((ROOT / f).read_text()):
            first = header.split("/")[0]
            if "/" not in header and (not header.endswith((".h", ".hpp")) or header in CPP_INCLUDES or
                                      not header[0].isupper()):
                if header not in CPP_INCLUDES:
                    continue  # the C or C++ standard library, POSIX
            if first in SYSTEM_DIRS:
                continue
            key = CPP_INCLUDES.get(first if "/" in header else header, "?")
            if key is not None:
                yield f, "#include <%s>" % header, key


FIND_PACKAGE = re.compile(r"find_package\(\s*([A-Za-z0-9_-]+)([^)]*)\)", re.S)


def cmake_uses(files):
    for f in files:
        if not (f.endswith("CMakeLists.txt") or f.endswith(".cmake")):
            continue
        text = re.sub(r'"[^"]*"|#[^\n]*', "", (ROOT / f).read_text())  # no strings, no comments
        # A find_package inside if(CATKIN_ENABLE_TESTING) ... endif() is for the tests.
        testing = [(m.start(), text.find("endif()", m.start())) for m in re.finditer(r"if\(CATKIN_ENABLE_TESTING\)", text)]
        for m in FIND_PACKAGE.finditer(text):
            when = "test_build" if any(a < m.start() < b for a, b in testing) else "build"
            name, rest = m.group(1), m.group(2)
            if name == "catkin" and "COMPONENTS" in rest:
                for component in rest.split("COMPONENTS", 1)[1].split():
                    yield f, when, "find_package(catkin COMPONENTS %s)" % component, component
            elif name in CMAKE_PACKAGES:
                if CMAKE_PACKAGES[name] is not None:
                    yield f, when, "find_package(%s)" % name, CMAKE_PACKAGES[name]
            else:
                yield f, when, "find_package(%s)" % name, name  # a ROS package: its own key


def launch_uses(files):
    for f in files:
        if not f.endswith((".launch", ".test")):
            continue
        root = ET.parse(ROOT / f).getroot()
        if f.endswith(".launch"):
            yield f, "a launch file", "roslaunch"
        for node in root.iter("node"):
            if node.get("pkg") != SELF:
                yield f, '<node pkg="%s">' % node.get("pkg"), node.get("pkg")
        for include in root.iter("include"):
            m = re.match(r"\$\(find ([a-z0-9_]+)\)", include.get("file", ""))
            if m and m.group(1) != SELF:
                yield f, "<include %s>" % include.get("file"), m.group(1)


TOOL = re.compile(r"""["'](%s)["']""" % "|".join(re.escape(t) for t in ROS_TOOLS))


def tool_uses(files):
    this_file = "test/" + Path(__file__).name  # its table names every tool
    for f in python_files(files):
        if f == this_file:
            continue
        for tool in TOOL.findall((ROOT / f).read_text()):
            yield f, 'runs "%s"' % tool, ROS_TOOLS[tool]


def all_uses():
    files = tracked()
    for f, what, key in python_uses(files):
        yield f, times(f), what, key
    for f, what, key in cpp_uses(files):
        yield f, {"build"} if "test" not in times(f) else {"test_build"}, what, key
    for f, when, what, key in cmake_uses(files):
        yield f, {when}, what, key
    for f, what, key in launch_uses(files):
        yield f, times(f), what, key
    for f, what, key in tool_uses(files):
        yield f, times(f), what, key


def declared():
    out = {}
    for element in ET.parse(ROOT / "package.xml").getroot():
        if element.tag.endswith("depend"):
            out.setdefault(element.text.strip(), set()).add(element.tag)
    return out


def pypi_requirements():
    names = set()
    for f in tracked():
        if os.path.basename(f) == "requirements.txt":
            for line in (ROOT / f).read_text().splitlines():
                m = re.match(r"\s*([A-Za-z0-9_.-]+)", line.split("#")[0])
                if m:
                    names.add(m.group(1).lower())
    return names


def problems(uses, deps, pypi):
    unmapped, undeclared = set(), set()
    for f, when, what, key in uses:
        if key == "?":
            unmapped.add("%s: %s (map it in test/test_package_dependencies.py)" % (f, what))
        elif key.startswith("pypi:"):
            if key[5:].lower() not in pypi:
                undeclared.add("%s: %s needs %s in a requirements.txt" % (f, what, key[5:]))
        else:
            for time_ in sorted(when):
                if not deps.get(key, set()) & set(KINDS[time_]):
                    undeclared.add("%s: %s needs %s as one of %s" % (f, what, key, "/".join(KINDS[time_])))
    return sorted(unmapped) + sorted(undeclared)


def test_package_xml_declares_every_dependency_the_code_has_for_when_it_is_needed():
    uses = list(all_uses())
    assert len(uses) > 100  # the scan sees the tree
    found = problems(uses, declared(), pypi_requirements())
    assert not found, "\n".join(found)


def test_an_import_nobody_declared_or_a_dependency_declared_for_the_wrong_time_is_reported(tmp_path, monkeypatch):
    module = sys.modules[__name__]
    monkeypatch.setattr(module, "ROOT", tmp_path)
    monkeypatch.setattr(module, "tracked", lambda: ["hil/new_tool.py", "drone_ros/report/test/test_new.py"])
    (tmp_path / "hil").mkdir()
    (tmp_path / "hil" / "new_tool.py").write_text("import pandas\nimport rosbag\nimport yaml\n")
    (tmp_path / "drone_ros" / "report" / "test").mkdir(parents=True)
    (tmp_path / "drone_ros" / "report" / "test" / "test_new.py").write_text("import scipy\n")
    deps = {"rosbag": {"test_depend"}, "python3-yaml": {"exec_depend"}, "python3-scipy": {"test_depend"}}
    assert problems(list(all_uses()), deps, set()) == [
        "hil/new_tool.py: import pandas (map it in test/test_package_dependencies.py)",
        "hil/new_tool.py: import rosbag needs rosbag as one of depend/exec_depend",
    ]
