"""A MAVLink telemetry log (.tlog) read back as MAVExplorer reads one (a helper, not a test): the
ground station's own tests and the report's test of a HiL flight's ground link both check what
microhard_gs wrote."""
import os

os.environ.setdefault("MAVLINK20", "1")
from pymavlink import mavutil  # noqa: E402  (MAVLINK20 first: the link is MAVLink 2)


def tlog_messages(path):
    """Every message of the tlog at path, in order, through pymavlink's mavlogfile; each carries
    its record time (_timestamp, s since the epoch) and link tag (_link: 3 sent by the vehicle, 0
    received from the ground station)."""
    log = mavutil.mavlink_connection(path, dialect="development")
    out = []
    while True:
        m = log.recv_msg()
        if m is None:
            return out
        out.append(m)
