"""The arduino node's link diagnostics as the link rostests read them (not named test_*.py:
pytest must not collect it)."""
import threading

import rospy
from diagnostic_msgs.msg import DiagnosticArray


class LinkDiagnostics:
    """The `arduino` node's latest "HA link" diagnostics: its counters and its level."""

    def __init__(self):
        self.lock = threading.Lock()
        self.values = {}
        self.level = None
        rospy.Subscriber("/diagnostics", DiagnosticArray, self._on_diagnostics, queue_size=100)

    def _on_diagnostics(self, m):
        for s in m.status:
            if s.name.endswith("HA link"):
                with self.lock:
                    self.values = {kv.key: kv.value for kv in s.values}
                    self.level = s.level

    def heard(self):
        with self.lock:
            return self.level is not None

    def ok(self):
        with self.lock:
            return self.level in (0, b"\x00")

    def counter(self, key):
        with self.lock:
            return float(self.values.get(key, "0"))
