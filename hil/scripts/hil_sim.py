#!/usr/bin/env python3
"""The HiL simulator node (hil/sim.py); started by launch/hil.launch. The hil package is on
PYTHONPATH once the devel or install space is sourced (setup.py, catkin_python_setup).

catkin gives this script ROS's Python (cmake/python.cmake, rule 3), but its PyPI dependencies
(jsbsim, pymavlink) live in the venv, so it runs itself under the venv's Python: $DRONE_ROS_VENV
if set, else the package's .venv (the source tree's); an install without either runs under the
Python that started it, which must import them."""
import os
import sys

import rospkg

PKG = rospkg.RosPack().get_path("drone_ros")
VENV_PYTHON = os.path.join(os.environ.get("DRONE_ROS_VENV", os.path.join(PKG, ".venv")), "bin", "python")
if sys.prefix == sys.base_prefix and os.path.exists(VENV_PYTHON):
    os.execv(VENV_PYTHON, [VENV_PYTHON, os.path.realpath(__file__)] + sys.argv[1:])
from hil.sim import main  # noqa: E402  (after the re-exec)

if __name__ == "__main__":
    sys.exit(main())
