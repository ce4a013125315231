"""The C99 packet encoder the HiL simulator builds its VN-200 packets with (vn_encode.c through
vn200_encode.py) writes the bytes the Python encoder wrote (vn200_emulation.binary_packet, kept
as the reference), for the two binary outputs the simulator streams and for random outputs over
every group and field, with random solutions: ordinary values, NaN with any payload, infinities,
signed zeros, subnormals, floats' limits and values no float holds, integers over their fields'
whole range. Where the Python encoder refuses a solution, so does the C one. Needs libvn200_encode.so of the catkin build on
LD_LIBRARY_PATH (the workspace's devel/setup.bash)."""
import math
import random
import struct

import pytest

from vn200_sim import vn200_emulation as ref  # noqa: E402
from vn200_sim import vn200_encode  # noqa: E402

HP_OUTPUT = (0x39, [0x0001 | 0x0002 | 0x0008 | 0x0010 | 0x0020 | 0x0040 | 0x0080 | 0x0100 | 0x0400 | 0x1000,
                    0, 0, 0x0008 | 0x0010 | 0x0200 | 0x0400, 0x0100, 0x0200 | 0x0400])  # output_config.cpp
HA_OUTPUT = (0x09, [0x0008 | 0x0020 | 0x0040 | 0x0080 | 0x0100 | 0x1000, 0, 0, 0x0010, 0, 0])  # hil/sensors.py
FLT_MAX = struct.unpack("<f", b"\xff\xff\x7f\x7f")[0]
EDGES = [0.0, -0.0, math.inf, -math.inf, math.nan, -math.nan, FLT_MAX, -FLT_MAX, 3.5e38, -1e300, 1e-45, 5e-324,
         1e-310, 180.0, -180.0, 359.999999, 1e9, 2.0 ** 24 + 1.0]


def value(r):
    """A double as a solution might carry it, or as no field expects it."""
    u = r.random()
    if u < 0.6:
        return r.uniform(-200.0, 200.0)
    if u < 0.8:
        return r.choice(EDGES)
    if u < 0.9:  # any bit pattern: NaNs with payloads, subnormals, huge and tiny values
        return struct.unpack("<d", r.getrandbits(64).to_bytes(8, "little"))[0]
    return r.uniform(-1.0, 1.0) * 10.0 ** r.randint(-40, 40)


def solution(r, edges=True):
    v = (lambda: value(r)) if edges else (lambda: r.uniform(-200.0, 200.0))
    v3 = lambda: (v(), v(), v())  # noqa: E731
    startup = r.choice([0, 1, 5 * 10 ** 9, r.getrandbits(63), 2 ** 64 - 1]) if edges else r.getrandbits(40)
    gps = r.choice([startup, ref.NS_PER_WEEK * 30000 + 7, 2 ** 64 - 1, r.getrandbits(63)]) \
        if edges else 2390 * ref.NS_PER_WEEK + startup
    return ref.Solution(startup_ns=startup, gps_ns=gps, ypr_deg=v3(), rate_radps=v3(), lla=v3(), vel_ned_mps=v3(),
                        accel_mps2=v3(), mag_gauss=v3(), temp_c=v(), pressure_kpa=v(),
                        ins_status=r.choice([0, 6, 0xFFFF, r.getrandbits(16)]), num_sats=r.getrandbits(8),
                        gps_fix=r.choice([0, 3, 255]), gps_pos_unc_m=v3(), gps_vel_unc_mps=v(), ypr_unc_deg=v3(),
                        ins_pos_unc_m=v(), ins_vel_unc_mps=v())


def output(r):
    """A random binary output: any groups, masks of documented fields or of any 16 bits."""
    groups = r.randint(1, 0x3F)
    masks = []
    for g in range(6):
        documented = sum(1 << b for b in range(16) if ref.FIELD_SIZES[g][b])
        masks.append(r.getrandbits(16) & (documented if r.random() < 0.8 else 0xFFFF))
    return groups, masks


def carries_velocity(groups, masks):
    return bool(groups & 0x01 and masks[0] & 0x0080 or groups & 0x20 and masks[5] & 0x0010)


def both(groups, masks, s):
    """(Python's packet or None if it refused, the C encoder's or None). The one refusal that is
    not the same: the Python encoder packs the velocity for every field it writes, so it also
    refuses a velocity no float holds in a packet without velocity; the C encoder checks the
    fields it writes. Such a packet is compared as the Python encoder writes it with the
    velocity left out."""
    try:
        want = ref.binary_packet(groups, masks, s)
    except (struct.error, OverflowError, ValueError):
        want = None
        if not carries_velocity(groups, masks):
            try:
                want = ref.binary_packet(groups, masks, ref.Solution(**dict(vars(s), vel_ned_mps=(0.0, 0.0, 0.0))))
            except (struct.error, OverflowError, ValueError):
                pass
    try:
        got = vn200_encode.PacketEncoder(groups, masks).packet(s)
    except ValueError:
        got = None
    return want, got


@pytest.mark.parametrize("out", [HP_OUTPUT, HA_OUTPUT], ids=["hp_port2", "ha_port1"])
def test_the_streams_the_simulator_writes_are_the_python_encoders_bytes(out):
    r = random.Random("vn200_encode/%d" % out[0])
    for i in range(1500):
        s = solution(r, edges=i % 3 == 0)
        want, got = both(out[0], out[1], s)
        assert got == want, (i, vars(s))
        if i % 3:  # in range: a packet, which passes its own CRC (the vn200 node's check)
            assert got is not None and len(got) == ref.packet_length(*out)
            assert ref.crc16(got[1:]) == 0


def test_random_outputs_and_solutions_give_the_python_encoders_bytes_or_its_refusal():
    r = random.Random("vn200_encode/random")
    written = refused = 0
    for i in range(8000):
        groups, masks = output(r)
        s = solution(r, edges=r.random() < 0.5)
        want, got = both(groups, masks, s)
        assert got == want, (i, groups, masks, vars(s))
        written += got is not None
        refused += got is None
    # Both kinds were exercised: values the fields hold and values they do not.
    assert written > 2000 and refused > 400, (written, refused)


def test_a_nan_keeps_its_sign_and_payload_as_struct_pack_does():
    nan = struct.unpack("<d", bytes.fromhex("0100000000c0ffff"))[0]  # negative quiet NaN, payload 1 << 38 | 1
    s = ref.Solution(startup_ns=1, gps_ns=2, ypr_deg=(nan, 0.0, 0.0), rate_radps=(0.0, nan, 0.0),
                     lla=(nan, 1.0, 2.0), vel_ned_mps=(0.0, 0.0, nan), accel_mps2=(0.0, 0.0, 0.0))
    want, got = both(*HP_OUTPUT, s)
    assert want is not None and got == want


@pytest.mark.parametrize("field,bad", [("startup_ns", -1), ("gps_ns", 2 ** 64), ("num_sats", 256),
                                       ("ins_status", 0x10000), ("temp_c", 3.5e38), ("ypr_deg", (math.inf, 0.0, 0.0))])
def test_a_value_its_field_cannot_hold_is_refused(field, bad):
    s = ref.Solution(startup_ns=1, gps_ns=2, ypr_deg=(1.0, 2.0, 3.0), rate_radps=(0.0, 0.0, 0.0),
                     lla=(1.0, 1.0, 2.0), vel_ned_mps=(0.0, 0.0, 0.0), accel_mps2=(0.0, 0.0, 0.0))
    setattr(s, field, bad)
    groups, masks = 0x3B, [0xFFFF & ~0x8000, 0x000F, 0, 0xFFFF, 0xFFFF, 0xFFFF]
    with pytest.raises((struct.error, OverflowError, ValueError)):
        ref.binary_packet(groups, masks, s)
    with pytest.raises(ValueError):
        vn200_encode.PacketEncoder(groups, masks).packet(s)
