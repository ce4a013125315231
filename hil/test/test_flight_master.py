"""A flight's master carries what roscore's would (hil/run_flight.py): the flight starts
rosmaster itself and sets roscore.xml's two parameters to what its `rosversion` commands print,
and every roslaunch of the flight loads a roscore.xml that runs no command."""
import os
import subprocess

import roslaunch.config
import roslaunch.xmlloader
import rospkg

from hil import ros_master, run_flight


def printed(*argv):
    return subprocess.run(list(argv), capture_output=True, text=True, check=True, timeout=60).stdout


def test_the_master_gets_what_roscores_rosversion_commands_print():
    assert ros_master.core_parameters() == {"rosversion": printed("rosversion", "roslaunch"),
                                            "rosdistro": printed("rosversion", "-d")}


def test_a_flights_roslaunch_loads_a_roscore_xml_that_runs_no_command(tmp_path, monkeypatch):
    env = dict(os.environ)
    run_flight.flight_etc_dir(str(tmp_path), env)
    monkeypatch.setenv("ROS_ETC_DIR", env["ROS_ETC_DIR"])
    config = roslaunch.config.ROSLaunchConfig()
    roslaunch.config.load_roscore(roslaunch.xmlloader.XmlLoader(), config, verbose=False)
    # The system's file has two parameters, each a `rosversion` process; this one none.
    assert config.params == {}
    assert [(n.package, n.type) for n in config.nodes_core] == [("rosout", "rosout")]


def test_python_nodes_keep_the_systems_logging_configuration(tmp_path):
    env = {k: v for k, v in os.environ.items() if k != "ROS_PYTHON_LOG_CONFIG_FILE"}
    system = rospkg.get_etc_ros_dir(env=env)
    run_flight.flight_etc_dir(str(tmp_path), env)
    assert os.path.normpath(env["ROS_ETC_DIR"]) == os.path.normpath(str(tmp_path / "etc"))
    assert os.path.normpath(os.path.dirname(env["ROS_PYTHON_LOG_CONFIG_FILE"])) == os.path.normpath(system)
    assert os.path.basename(env["ROS_PYTHON_LOG_CONFIG_FILE"]).startswith("python_logging.")
