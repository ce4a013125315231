#!/usr/bin/env python3
"""The HA as Cortex-M3 machine code in QEMU, in ha_sil's place (hil/ha_qemu.py); started by
launch/hil.launch with ha:=qemu. The hil package is on PYTHONPATH once the workspace is
sourced; it needs nothing but the standard library and qemu-system-arm."""
import sys


from hil.ha_qemu import main

if __name__ == "__main__":
    sys.exit(main())
