"""The VN-200 as the simulators see it: its registers and solution (vn200_emulation) and its binary
packets, encoded by the driver's own C (vn200_encode, through libvn200_encode.so). fake_vn200.py and
the HiL's sensors use it; the driver itself (C++) does not."""
