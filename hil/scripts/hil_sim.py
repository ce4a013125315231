#!/usr/bin/env python3
"""The HiL simulator node (hil/sim.py); started by launch/DG808_hil.launch. Its PyPI
dependencies (jsbsim, pymavlink) live in the repository's .venv (made by make deps from
/usr/bin/python3 with the system's ROS packages), so it runs itself under that Python."""
import os
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.realpath(__file__)), "..", ".."))
VENV_PYTHON = os.path.join(ROOT, ".venv", "bin", "python")
if sys.prefix == sys.base_prefix and os.path.exists(VENV_PYTHON):
    os.execv(VENV_PYTHON, [VENV_PYTHON, os.path.realpath(__file__)] + sys.argv[1:])
sys.path.insert(0, ROOT)
from hil.sim import main  # noqa: E402

if __name__ == "__main__":
    sys.exit(main())
