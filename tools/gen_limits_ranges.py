#!/usr/bin/env python3
"""stack_tools/gen_limits_ranges.py as a command, for the build (CMake runs it by its path): beside the
package folder, it imports the package without a sourced workspace.

usage: gen_limits_ranges.py LIMITS_RANGES_YAML OUTPUT_HEADER"""
import sys

from stack_tools.gen_limits_ranges import main

if __name__ == "__main__":
    sys.exit(main(sys.argv))
