#!/usr/bin/env python3
"""The aircraft YAML checker as a command (stack_tools/check_config.py says what it checks):
launch/check_config.launch runs it by its path, $(find drone_ros)/tools/, in devel and install.

usage: check_config.py PATH..."""
import sys

from stack_tools.check_config import main

if __name__ == "__main__":
    sys.exit(main(sys.argv))
