#!/usr/bin/env python3
"""The simulator's end of a real Due in the loop, in ha_sil's place (hil/ha_due.py); started by
launch/hil.launch with ha:=due. The hil package is on PYTHONPATH once the workspace is
sourced; it needs nothing but the standard library."""
import sys

from hil.ha_due import main

if __name__ == "__main__":
    sys.exit(main())
