"""The ground floor shared across languages, for Python: the C that the Due and the HP nodes run
(geodesy, the messages' CRC), bound through ctypes from libstack_common.so, and the units.

- stack_common.geo: the stack's one latitude/longitude <-> north/east conversion (geo_wgs84.c).
- stack_common.crc: the CRC-32 a ServoCommand or an OperatorCommand carries (hp_command.c).
- stack_common.native: the build's C libraries for ctypes (this package's, vn200_sim's encoder).
- stack_common.rospy_shutdown: lets a rospy node exit when told to (rospy alone waits 0.6 s).
- stack_common.units: the foot and standard gravity (pure Python: the build's generators use it
  before the library exists); the test holds the foot to the C's.
"""
