"""The unit conversions and physical constants the Python side shares, defined once.

The stack mixes SI (JSBSim's metric outputs, the VN-200's registers, bag exports) with the
project's feet and ft/s (limits.yaml, the HA core). The international foot is exactly 0.3048 m
and standard gravity exactly 9.80665 m/s^2, so every derived value follows from those two. Pure
Python, so the build's generators can use it before libstack_common.so exists; test_stack_common
holds FT_PER_M to the C's GEO_FT_PER_M."""

M_PER_FT = 0.3048
FT_PER_M = 1.0 / M_PER_FT
G_MPS2 = 9.80665
G_FTPS2 = G_MPS2 * FT_PER_M  # 32.174...
