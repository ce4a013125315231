"""What a ground station shows: holds the port microhard_gs sends its telemetry to, as
QGroundControl would (and, like it, sends a GCS HEARTBEAT every second, which is also what
brings the node's telemetry back to this port after another client has talked to it), and
keeps every GLOBAL_POSITION_INT and HOME_POSITION with the simulated time it arrived at, so the
verdict can hold the ground station's view against the truth."""
import os
import socket
import threading
import time
from collections import namedtuple

os.environ.setdefault("MAVLINK20", "1")
from pymavlink.dialects.v20 import development as mavlink  # noqa: E402

Position = namedtuple("Position", "t_s lat_deg lon_deg relative_alt_m")
Home = namedtuple("Home", "lat_deg lon_deg alt_m")


class GsMonitor:
    def __init__(self, port, gs_port, now_s):
        self.now_s = now_s  # the simulated time, read when a datagram arrives
        self.gs_addr = ("127.0.0.1", gs_port)
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.sock.bind(("127.0.0.1", port))
        self.sock.settimeout(0.2)
        self.parser = mavlink.MAVLink(None)
        self.parser.robust_parsing = True
        self.sender = mavlink.MAVLink(None, srcSystem=255, srcComponent=190)  # QGroundControl's ids
        self.next_heartbeat = 0.0
        self.positions = []
        self.home = None
        self.datagrams = 0
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)
        self._thread.start()

    def _run(self):
        while not self._stop.is_set():
            if time.monotonic() >= self.next_heartbeat:
                self.next_heartbeat = time.monotonic() + 1.0
                hb = self.sender.heartbeat_encode(mavlink.MAV_TYPE_GCS, mavlink.MAV_AUTOPILOT_INVALID, 0, 0,
                                                  mavlink.MAV_STATE_ACTIVE)
                try:
                    self.sock.sendto(hb.pack(self.sender), self.gs_addr)
                except OSError:
                    pass
            try:
                data = self.sock.recv(65536)
            except socket.timeout:
                continue
            except OSError:
                return
            if self._stop.is_set():
                return
            self.datagrams += 1
            t_s = self.now_s()
            for m in self.parser.parse_buffer(data) or []:
                kind = m.get_type()
                if kind == "GLOBAL_POSITION_INT":
                    self.positions.append(Position(t_s, m.lat * 1e-7, m.lon * 1e-7, m.relative_alt * 1e-3))
                elif kind == "HOME_POSITION":
                    self.home = Home(m.latitude * 1e-7, m.longitude * 1e-7, m.altitude * 1e-3)

    def stop(self):
        self._stop.set()
        try:
            # Wakes the thread's receive now, not at its 0.2 s timeout.
            self.sock.sendto(b"", self.sock.getsockname())
        except OSError:
            pass
        self._thread.join(timeout=2.0)
        self.sock.close()
