"""A mission as a ground station holds it (QGC WPL 110 file) and its upload to microhard_gs over
MAVLink 2 on UDP, item by item, as QGroundControl does it (MISSION_COUNT, then MISSION_ITEM_INT
for each MISSION_REQUEST_INT, until MISSION_ACK)."""
import math
import os
import time
from collections import namedtuple

os.environ.setdefault("MAVLINK20", "1")
from pymavlink import mavutil  # noqa: E402

Item = namedtuple("Item", "lat_deg lon_deg height_m")
Plan = namedtuple("Plan", "home items")  # home: (lat_deg, lon_deg, alt_m)

# Waypoint heights are above home.
UPLOAD_FRAME = 3  # MAV_FRAME_GLOBAL_RELATIVE_ALT, what QGroundControl puts in every waypoint


def read_wpl(path):
    """Reads a QGC WPL 110 file: line 0 is home (frame 0, altitude above the ellipsoid datum),
    then NAV_WAYPOINT items in MAV_FRAME_GLOBAL_RELATIVE_ALT (height above home, m)."""
    with open(path) as f:
        lines = [ln.strip() for ln in f if ln.strip()]
    if not lines or not lines[0].startswith("QGC WPL 110"):
        raise ValueError("%s: not a QGC WPL 110 file" % path)
    home, items = None, []
    for n, ln in enumerate(lines[1:], start=2):
        cols = ln.split("\t")
        if len(cols) != 12:
            raise ValueError("%s:%d: %d columns, expected 12" % (path, n, len(cols)))
        seq, frame, cmd = int(cols[0]), int(cols[2]), int(cols[3])
        lat, lon, alt = float(cols[8]), float(cols[9]), float(cols[10])
        if seq == 0:
            home = (lat, lon, alt)
        elif cmd == 16 and frame == 3:
            items.append(Item(lat, lon, alt))
        else:
            raise ValueError("%s:%d: only NAV_WAYPOINT (16) in frame 3 after home" % (path, n))
    if home is None or not items:
        raise ValueError("%s: needs home and at least one waypoint" % path)
    return Plan(home, items)


def bearing_deg(lat1, lon1, lat2, lon2):
    y = math.sin(math.radians(lon2 - lon1)) * math.cos(math.radians(lat2))
    x = math.cos(math.radians(lat1)) * math.sin(math.radians(lat2)) - \
        math.sin(math.radians(lat1)) * math.cos(math.radians(lat2)) * math.cos(math.radians(lon2 - lon1))
    return math.degrees(math.atan2(y, x)) % 360.0


def upload(plan, host, vehicle_port, timeout_s=10.0, target_system=1, target_component=1):
    """Uploads plan.items to microhard_gs listening on host:vehicle_port (it answers the sender);
    returns the MISSION_ACK result name, or "timeout"."""
    link = mavutil.mavlink_connection("udpout:%s:%d" % (host, vehicle_port), source_system=255,
                                      source_component=190, input=False)
    try:
        mav = link.mav
        mav.mission_count_send(target_system, target_component, len(plan.items), 0)
        deadline = time.monotonic() + timeout_s
        while time.monotonic() < deadline:
            msg = link.recv_match(type=["MISSION_REQUEST_INT", "MISSION_REQUEST", "MISSION_ACK"],
                                  blocking=True, timeout=0.5)
            if msg is None:
                continue
            if msg.get_type() == "MISSION_ACK":
                return mavutil.mavlink.enums["MAV_MISSION_RESULT"][msg.type].name
            seq = msg.seq
            if not 0 <= seq < len(plan.items):
                continue
            it = plan.items[seq]
            mav.mission_item_int_send(target_system, target_component, seq, UPLOAD_FRAME,
                                      mavutil.mavlink.MAV_CMD_NAV_WAYPOINT, 0, 1, 0.0, 0.0, 0.0,
                                      0.0, int(round(it.lat_deg * 1e7)),
                                      int(round(it.lon_deg * 1e7)), it.height_m, 0)
        return "timeout"
    finally:
        link.close()
