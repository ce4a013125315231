"""The CRC-32 that a ServoCommand or an OperatorCommand carries over the ROS serialization of its
fields before crc32: ha_crc32 of hp_command.c, the function the HA checks it with."""
from .native import library


def crc32(data):
    """CRC-32/ISO-HDLC of bytes (zlib's crc32), computed by the HA's own ha_crc32."""
    data = bytes(data)
    return library().ha_crc32(data, len(data))
