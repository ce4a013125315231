#!/usr/bin/env python3
"""The HiL simulator node (hil/sim.py); started by launch/DG808_hil.launch. It finds the hil
package through the package path (rospack find drone_ros): the source tree from a devel space,
share/drone_ros from an install, where hil/CMakeLists.txt installs the package and the files it
imports, laid out as in the source tree. Its PyPI dependencies (jsbsim, pymavlink) live in a
virtualenv made by make deps from /usr/bin/python3 with the system's ROS packages, so it runs
itself under that Python: $DRONE_ROS_VENV if set, else the package's .venv (the source tree's);
an install without either runs under the Python that started it, which must import them."""
import os
import sys

import rospkg

PKG = rospkg.RosPack().get_path("drone_ros")
VENV_PYTHON = os.path.join(os.environ.get("DRONE_ROS_VENV", os.path.join(PKG, ".venv")), "bin", "python")
if sys.prefix == sys.base_prefix and os.path.exists(VENV_PYTHON):
    os.execv(VENV_PYTHON, [VENV_PYTHON, os.path.realpath(__file__)] + sys.argv[1:])
sys.path.insert(0, PKG)
from hil.sim import main  # noqa: E402

if __name__ == "__main__":
    sys.exit(main())
