#!/usr/bin/env python3
"""stack_tools/gen_aircraft_config.py as a command, for the build (CMake runs it by its path): beside the
package folder, it imports the package without a sourced workspace.

usage: gen_aircraft_config.py LIMITS_YAML OUT_H   (OUT_H - writes to stdout)
       gen_aircraft_config.py --types OUT_H        (HaAircraftConfig itself)"""
import sys

from stack_tools.gen_aircraft_config import main

if __name__ == "__main__":
    sys.exit(main(sys.argv))
