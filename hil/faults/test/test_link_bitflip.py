"""Bit flips on the HP-HA link (in the bytes on the pty between the arduino node and the HA, the
frame's own checksum made to match): the HA's CRC-32 check catches them, the corrupted command
never reaches a servo, and the HA has the servos the period the first one arrives."""
from stack_testing.fault_flight import assert_property, fly


def test_bit_flips_in_the_command_payload_are_caught_by_the_crc():
    s = fly("link_bitflip", at_s=15.0, duration_s=2.0, params=["target=payload"])
    assert_property(s, takeover_due=True)


def test_bit_flips_in_the_crc_itself_are_caught():
    s = fly("link_bitflip", at_s=15.0, duration_s=2.0, params=["target=crc"], flight_s=25.0)
    assert_property(s, takeover_due=True)
