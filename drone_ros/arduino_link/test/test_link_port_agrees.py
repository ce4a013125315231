"""The HA-HP link's rate is set in four places that must agree: the Due sketch's port and baud
(arduino_ha/src/board_due/due_config.h), the flight launch and the node's own launch file, and
the node's built-in default (link_params.h). A mismatch does not fail loudly in flight: the node
just sees garbage and counts it. These tests fail instead."""
import pathlib
import re
import xml.etree.ElementTree as ET

ROOT = pathlib.Path(__file__).resolve().parents[3]
DUE_CONFIG = ROOT / "arduino_ha" / "src" / "board_due" / "due_config.h"


def due_define(name):
    m = re.search(r"^#define %s (\S+)" % name, DUE_CONFIG.read_text(), re.M)
    assert m, "%s not defined in %s" % (name, DUE_CONFIG)
    return m.group(1)


def launch_arg_default(path, name):
    for arg in ET.parse(path).getroot().iter("arg"):
        if arg.get("name") == name:
            return arg.get("default")
    raise AssertionError("no <arg name=%s> in %s" % (name, path))


def test_the_sketch_talks_on_the_programming_port_unless_built_for_the_native_one():
    assert due_define("DUE_HP_LINK_PORT") == "DUE_HP_LINK_PORT_PROGRAMMING"


def test_the_sketchs_rate_is_the_flight_launchs_and_the_nodes():
    due_baud = int(due_define("DUE_HP_LINK_BAUD").rstrip("uU"))
    assert due_baud == 250000, "the link budget (drone_ros/arduino_link/README.md) assumes 250000"
    assert int(launch_arg_default(ROOT / "launch" / "flight.launch", "arduino_baud")) == due_baud
    assert int(launch_arg_default(ROOT / "drone_ros" / "arduino_link" / "launch" / "arduino.launch", "baud")) == due_baud
    params = (ROOT / "drone_ros" / "arduino_link" / "src" / "link_params.h").read_text()
    assert re.search(r"int baud = %d;" % due_baud, params), "LinkParams' default baud differs"
