#!/usr/bin/env python3
"""The HA as Cortex-M3 machine code in QEMU, in ha_sil's place (hil/ha_qemu.py); started by
launch/DG808_hil.launch with ha:=qemu. It finds the hil package through the package path, as
hil_sim.py does; it needs nothing but the standard library and qemu-system-arm."""
import sys

import rospkg

sys.path.insert(0, rospkg.RosPack().get_path("drone_ros"))
from hil.ha_qemu import main  # noqa: E402

if __name__ == "__main__":
    sys.exit(main())
