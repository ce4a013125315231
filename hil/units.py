"""The unit conversions and physical constants the HiL's modules share, defined once.

The HiL mixes SI (JSBSim's metric outputs, the VN-200's registers) with the project's feet and
ft/s (limits.yaml, the HA core). The foot is exactly 0.3048 m and standard gravity exactly
9.80665 m/s^2, so every derived value here follows from those two.
"""

M_PER_FT = 0.3048
FT_PER_M = 1.0 / M_PER_FT
G_MPS2 = 9.80665
G_FTPS2 = G_MPS2 * FT_PER_M  # 32.174...
