#!/usr/bin/env python3
"""Writes the checked-in seed corpus of fuzz_gs_core (run once; seeds are small binary files).
Byte 0 of each seed selects the harness mode (bit0 signing, bit1 the HA's home given, bit2 telemetry,
bit3 decision changes), byte 1 seeds the chunking; the rest is what the link delivers."""
import os
import sys

os.environ["MAVLINK20"] = "1"
from pymavlink.dialects.v20 import common as mavlink  # noqa: E402

HERE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "corpus")
KEY = bytes(range(1, 33))


class Sink:
    def write(self, _):
        pass


def gcs(signed=False):
    mav = mavlink.MAVLink(Sink(), srcSystem=255, srcComponent=190)
    if signed:
        mav.signing.secret_key = KEY
        mav.signing.sign_outgoing = True
        mav.signing.timestamp = (1795000000 - 1420070400) * 100000
    return mav


def pack(mav, msg):
    return msg.pack(mav)


def mission(mav, count, height_m=60.0, legacy=False):
    out = pack(mav, mav.mission_count_encode(1, 1, count, 0))
    for seq in range(count):
        lat, lon = 40.11 + seq * 1e-4, -88.22
        if legacy:
            out += pack(mav, mav.mission_item_encode(1, 1, seq, 3, 16, 0, 1, 0, 0, 0, 0, lat, lon, height_m, 0))
        else:
            out += pack(mav, mav.mission_item_int_encode(1, 1, seq, 6, 16, 0, 1, 0, 0, 0, 0,
                                                         int(lat * 1e7), int(lon * 1e7), height_m, 0))
    return out


def main():
    os.makedirs(HERE, exist_ok=True)
    m = gcs()
    seeds = {
        "heartbeat": bytes([0, 1]) + pack(m, m.heartbeat_encode(6, 8, 0, 0, 4)),
        "param_list_read_set": bytes([0, 2]) + pack(m, m.param_request_list_encode(1, 1)) +
        pack(m, m.param_request_read_encode(1, 1, b"mpf_radius", -1)) +
        pack(m, m.param_request_read_encode(1, 1, b"", 3)) +
        pack(m, m.param_set_encode(1, 1, b"Q_weight", 3.5, 9)) +
        pack(m, m.param_set_encode(1, 1, b"path_select", 2.0, 6)),
        "mission_upload": bytes([6, 3]) + mission(m, 4),
        "mission_upload_legacy": bytes([6, 4]) + mission(m, 3, legacy=True),
        "mission_too_high": bytes([6, 5]) + mission(m, 2, height_m=200.0),
        "mission_download_clear": bytes([6, 6]) + mission(m, 2) +
        pack(m, m.mission_request_list_encode(1, 1, 0)) + pack(m, m.mission_request_int_encode(1, 1, 0, 0)) +
        pack(m, m.mission_request_encode(1, 1, 1, 0)) + pack(m, m.mission_ack_encode(1, 1, 0, 0)) +
        pack(m, m.mission_clear_all_encode(1, 1, 0)),
        "commands": bytes([14, 7]) +
        pack(m, m.command_long_encode(1, 1, 176, 0, 1, 1, 0, 0, 0, 0, 0)) +
        pack(m, m.command_long_encode(1, 1, 246, 0, 0, 1, 0, 0, 0, 0, 0)) +
        pack(m, m.command_long_encode(1, 1, 310, 0, 0, 0, 0, 0, 0, 0, 0)) +
        pack(m, m.command_long_encode(1, 1, 512, 0, 148, 0, 0, 0, 0, 0, 0)) +
        pack(m, m.command_int_encode(1, 1, 0, 176, 0, 0, 1, 0, 0, 0, 0, 0, 0)),
        "garbage_then_frame": bytes([0, 8]) + b"\xfd\x09\x00\x00\xfe\xfe" + bytes(range(40)) +
        pack(m, m.param_request_list_encode(1, 1)),
    }
    s = gcs(signed=True)
    seeds["signed_command_and_mission"] = bytes([7, 9]) + pack(s, s.command_long_encode(1, 1, 176, 0, 1, 0, 0, 0, 0, 0, 0)) + mission(s, 2)
    seeds["unsigned_with_signing_on"] = bytes([7, 10]) + pack(m, m.command_long_encode(1, 1, 176, 0, 1, 1, 0, 0, 0, 0, 0)) + mission(m, 1)
    for name, blob in seeds.items():
        with open(os.path.join(HERE, name), "wb") as f:
            f.write(blob)
    print("wrote %d seeds to %s" % (len(seeds), HERE))
    return 0


if __name__ == "__main__":
    sys.exit(main())
