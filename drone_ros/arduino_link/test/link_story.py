#!/usr/bin/env python3
"""Stories of the HA-HP link, end to end: the SIL HA (real core, real link device side) on a
pseudo-terminal, the real `arduino` node, and a wire tap between them. Run by link_sil.test."""
import collections
import os
import re
import shutil
import signal
import struct
import subprocess
import tempfile
import threading
import time
import unittest
import zlib

import rospy
import rostest
from rosgraph_msgs.msg import Log
from std_msgs.msg import String

# catkin_python_setup() makes devel/lib/python3 at the first configure and refreshes the cached
# environment, so even a fresh workspace's `run_tests` finds the messages.
from drone_ros.msg import DecisionStatus, ServoCommand, pwm

from link_diagnostics import LinkDiagnostics  # noqa: E402
from stack_testing.story_wait import wait_for  # noqa: E402
from stack_testing.processes import end_process  # noqa: E402
from stack_testing.wire_tap import WireTap, frame, topic_info  # noqa: E402

WS = os.environ.get("DRONE_ROS_WS", "")


def find_sil():
    for root in filter(None, os.environ.get("CMAKE_PREFIX_PATH", "").split(":") + [WS + "/devel"]):
        path = os.path.join(root, "lib", "drone_ros", "ha_sil")
        if os.path.exists(path):
            return path
    raise RuntimeError("ha_sil not built")


def servo_command(seq, good_crc=True):
    cmd = ServoCommand(seq=seq, throttle=0.5, elevator_deg=-1.0, aileron_deg=2.0, rudder_deg=0.5,
                       alpha_est_deg=3.0, beta_est_deg=0.0, estimator_converged=True,
                       sensor_links_healthy=True)
    cmd.stamp = rospy.Time.now()
    fields = struct.pack("<III6fBB", cmd.seq, cmd.stamp.secs, cmd.stamp.nsecs, cmd.throttle,
                         cmd.elevator_deg, cmd.aileron_deg, cmd.rudder_deg, cmd.alpha_est_deg,
                         cmd.beta_est_deg, 1, 1)
    crc = zlib.crc32(fields) & 0xFFFFFFFF
    cmd.crc32 = crc if good_crc else crc ^ 0x00010000  # one flipped bit the 8-bit sum cannot see
    return cmd


class Watch:
    """Latest messages and a history, thread-safe."""

    def __init__(self):
        self.lock = threading.Lock()
        self.pwm = []
        self.status = None
        self.logs = []
        rospy.Subscriber("pwm", pwm, self._pwm, queue_size=1000)
        rospy.Subscriber("decision_status", DecisionStatus, self._status, queue_size=100)
        rospy.Subscriber("/rosout", Log, self._log, queue_size=100)

    def _pwm(self, m):
        with self.lock:
            self.pwm.append((time.time(), m.usbstatus))

    def _status(self, m):
        with self.lock:
            self.status = m

    def _log(self, m):
        with self.lock:
            self.logs.append(m.msg)

    def device_errors(self):
        """The HA's own drop counters from its latest "[HA] link errors: name N ..." log (the SIL
        sends one whenever it drops something new); all zero before the first."""
        with self.lock:
            reports = [m for m in self.logs if m.startswith("[HA] link errors:")]
        if not reports:
            return collections.defaultdict(int)
        return collections.defaultdict(int, {k: int(v) for k, v in re.findall(r"(\w+) (\d+)", reports[-1])})


class LinkStories(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("link_story")
        cls.tmp = tempfile.mkdtemp(prefix="drone_ros_link_")
        cls.node_port = rospy.get_param("~node_port")
        cls.device_port = os.path.join(cls.tmp, "due")
        cls.watch = Watch()
        cls.diag = LinkDiagnostics()
        cls.pub = rospy.Publisher("servo_op", ServoCommand, queue_size=100, tcp_nodelay=True)
        cls.sil = subprocess.Popen([find_sil(), "--port", cls.device_port, "--rate-hz", "100",
                                     "--param", "link_probe", "--unplug-ms", "800"])
        cls.tap = WireTap(cls.device_port, cls.node_port)
        cls.tap.start()
        cls.seq = 1000

    @classmethod
    def tearDownClass(cls):
        cls.tap.close()
        end_process(cls.sil, grace_s=5)
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def link_up(self):
        with self.watch.lock:
            return bool(self.watch.pwm) and self.watch.pwm[-1][1] == 1

    def send_commands(self, count, good_crc=True, repeat=False, step=1):
        for _ in range(count):
            if not repeat:
                type(self).seq += step
            self.pub.publish(servo_command(self.seq, good_crc))
            time.sleep(0.01)

    def status(self):
        with self.watch.lock:
            return self.watch.status

    def test_01_sensors_flow_from_the_ha_with_time_synced_and_its_log_forwarded(self):
        wait_for(self.link_up, 20.0, "/pwm with usbstatus 1")
        wait_for(lambda: self.status() is not None and self.status().stamp.secs > 0, 5.0,
                 "/decision_status stamped with synced ROS time")
        self.assertLess(abs(self.status().stamp.to_sec() - rospy.Time.now().to_sec()), 2.0)
        wait_for(lambda: any("[HA] HA SIL link up" in m for m in self.watch.logs), 5.0, "device log on rosout")
        wait_for(self.diag.ok, 5.0, "diagnostics OK")

    def test_01b_the_ha_reads_a_parameter_through_the_host(self):
        wait_for(lambda: any("[HA] param link_probe: 42" in m for m in self.watch.logs), 10.0,
                 "the device's parameter request answered with 42 and logged back")

    def test_02_valid_commands_reach_the_ha_core(self):
        wait_for(self.link_up, 20.0, "link up")
        wait_for(lambda: self.pub.get_num_connections() > 0, 5.0, "arduino subscribed to servo_op")
        self.send_commands(30)
        wait_for(lambda: self.status().last_seq == self.seq, 3.0, "last_seq to follow the commands")
        self.assertEqual(self.status().reasons & (DecisionStatus.REASON_INTEGRITY | DecisionStatus.REASON_FROZEN), 0)

    def test_03_corrupt_command_is_rejected_by_the_ha(self):
        self.send_commands(20)
        self.send_commands(5, good_crc=False)
        wait_for(lambda: self.status().reasons & DecisionStatus.REASON_INTEGRITY, 3.0, "REASON_INTEGRITY")

    def test_04_repeated_command_is_rejected_as_a_frozen_hp(self):
        self.send_commands(20)
        self.send_commands(10, repeat=True)
        wait_for(lambda: self.status().reasons & DecisionStatus.REASON_FROZEN, 3.0, "REASON_FROZEN")

    def test_05_out_of_order_command_is_rejected(self):
        self.send_commands(20)
        self.send_commands(5, step=-3)
        wait_for(lambda: self.status().reasons & DecisionStatus.REASON_FROZEN, 3.0,
                 "REASON_FROZEN for a sequence number that went backwards")

    def test_06_bad_bytes_both_ways_are_counted_on_both_ends_and_the_link_carries_on(self):
        wait_for(self.link_up, 10.0, "link up")
        before = {k: self.diag.counter(k) for k in
                  ("bytes_skipped", "bad_checksum", "oversized", "unknown_topic", "bad_length_checksum")}
        device_before = self.watch.device_errors()
        good = frame(125, bytes(66))
        bad_sum = bytearray(frame(126, bytes(68)))
        bad_sum[-1] ^= 0x5A
        flipped = bytearray(good)
        flipped[20] ^= 0x04
        bad_len = bytearray(good)
        bad_len[4] ^= 0xFF
        for chunk in (b"\x00garbage\x13\x37", bytes(bad_sum), bytes([0xFF, 0xFE, 0xFF, 0xFF, 0x01, 1, 2]),
                      frame(4242, b"\x01\x02"), bytes(flipped), bytes(bad_len)):
            self.tap.inject_to_node(chunk)
            self.tap.inject_to_device(chunk)
            time.sleep(0.02)
        self.tap.inject_to_node(frame(4243, b"split across reads"), split=True)  # in 3-byte pieces
        wait_for(lambda: self.diag.counter("bytes_skipped") > before["bytes_skipped"], 5.0, "skipped bytes counted")
        wait_for(lambda: self.diag.counter("bad_checksum") >= before["bad_checksum"] + 2, 5.0, "bad checksums")
        wait_for(lambda: self.diag.counter("oversized") > before["oversized"], 5.0, "absurd length counted")
        wait_for(lambda: self.diag.counter("unknown_topic") >= before["unknown_topic"] + 2, 5.0,
                 "unknown topics counted, including the split frame")
        wait_for(lambda: self.diag.counter("bad_length_checksum") > before["bad_length_checksum"], 5.0,
                 "bad length checksum counted")
        # The HA dropped the same kinds of bad input on its side, and says so.
        expected = {"bytes_skipped": 1, "bad_checksum": 2, "oversized": 1, "unknown_topic": 1, "bad_length_checksum": 1}

        def device_counted():
            now = self.watch.device_errors()
            return all(now[k] - device_before[k] >= n for k, n in expected.items())

        wait_for(device_counted, 5.0, "the HA's own counters to show every kind of injected bad frame")
        # And the link carries on both ways.
        self.send_commands(20)
        wait_for(lambda: self.status().last_seq == self.seq, 3.0, "commands still reach the HA")
        self.assertTrue(self.link_up())
        self.assertIsNone(self.sil.poll(), "the SIL must not have died")

    def test_06b_announcements_and_payloads_the_node_cannot_take_are_counted_not_fatal(self):
        # Well-formed frames (right checksums) whose content ROS refuses: each of these used to
        # throw out of advertise/subscribe and abort the node. A flaky or foreign device must
        # not take the HP's end of the link down with it.
        wait_for(self.link_up, 10.0, "link up")
        bad_before = self.diag.counter("bad_payload")
        md5 = String._md5sum
        refused = [
            frame(0, topic_info(140, "bad name!", "std_msgs/String", md5)),   # not a ROS name
            frame(1, topic_info(141, "also bad!", "std_msgs/String", md5)),
            frame(0, topic_info(142, "", "std_msgs/String", md5)),            # no name at all
            frame(0, topic_info(143, "garbage_type", "*", "*")),              # roscpp refuses '*'
            frame(0, topic_info(144, "empty_type", "", "")),
            frame(0, topic_info(145, "odd_type", "no slash \x01", md5)),
            frame(1, topic_info(146, "odd_md5", "std_msgs/String", "not-an-md5")),
            frame(0, topic_info(7, "reserved_id", "std_msgs/String", md5)),   # rosserial's log id
            frame(126, bytes(10)),  # /decision_status cut short: must not reach ROS subscribers
        ]
        for f in refused:
            self.tap.inject_to_node(f)
            time.sleep(0.02)
        wait_for(lambda: self.diag.counter("bad_payload") >= bad_before + len(refused), 5.0,
                 "every refused frame counted as a bad payload")
        # The same node carries on both ways.
        self.send_commands(20)
        wait_for(lambda: self.status().last_seq == self.seq, 3.0, "commands still reach the HA")
        self.assertTrue(self.link_up())

    def test_06c_operator_request_changed_under_the_frame_checksum_is_dropped_by_the_ha(self):
        # A sealed SELECT_HP whose command byte went one up (SELECT_HA) and whose request id's
        # low byte went one down: rosserial's 8-bit sum still matches, the request's CRC-32 not.
        wait_for(self.link_up, 10.0, "link up")
        device_before = self.watch.device_errors()
        fields = struct.pack("<IIBI?ddd", 1700000000, 0, 1, 4242, False, 0.0, 0.0, 0.0)
        sealed = bytearray(fields + struct.pack("<I", zlib.crc32(fields) & 0xFFFFFFFF))
        sealed[8] += 1   # SELECT_HP -> SELECT_HA
        sealed[9] -= 1   # request id 4242 -> 4241
        self.tap.inject_to_device(frame(101, bytes(sealed)))  # the HA's operator_command topic
        wait_for(lambda: self.watch.device_errors()["operator_bad_crc"] == device_before["operator_bad_crc"] + 1,
                 5.0, "the HA to count the request's bad CRC")
        self.send_commands(20)
        wait_for(lambda: self.status().last_seq == self.seq, 3.0, "commands still reach the HA")
        self.assertEqual(self.status().reasons & DecisionStatus.REASON_GROUND_COMMAND, 0,
                         "the altered request must not have been executed")

    def test_07_unplug_and_replug_is_survived_with_the_gap_reported(self):
        wait_for(self.link_up, 10.0, "link up")
        opens_before = self.diag.counter("port_opens")
        outages_before = self.diag.counter("outages")
        self.tap.unplug()
        t_unplug = time.time()
        wait_for(lambda: not self.link_up(), 3.0, "/pwm usbstatus 0 after the unplug")
        time.sleep(1.0)
        self.tap.plug()
        wait_for(self.link_up, 10.0, "/pwm usbstatus 1 after the replug")
        # Diagnostics come once a second: wait for the one that reports the link back up.
        wait_for(lambda: self.diag.counter("outages") == outages_before + 1 and self.diag.ok(), 3.0,
                 "one outage reported, link OK again")
        gap = self.diag.counter("last_gap_s")
        self.assertGreater(gap, 0.8)
        self.assertLess(gap, time.time() - t_unplug + 1.0)
        # The same node process reopened the port (a restarted node would count from 1 again).
        self.assertGreater(self.diag.counter("port_opens"), opens_before)
        self.send_commands(20)
        wait_for(lambda: self.status().last_seq == self.seq, 3.0, "commands flow again after the replug")

    def test_08_usb_loss_on_the_ha_side_is_survived_too(self):
        wait_for(self.link_up, 10.0, "link up")
        outages_before = self.diag.counter("outages")
        self.sil.send_signal(signal.SIGUSR1)  # the Due's end drops off the bus for 0.8 s
        wait_for(lambda: not self.link_up(), 3.0, "/pwm usbstatus 0 after the HA dropped off")
        wait_for(self.link_up, 10.0, "/pwm usbstatus 1 once the HA is back")
        wait_for(lambda: self.diag.counter("outages") == outages_before + 1 and self.diag.ok(), 3.0,
                 "the outage reported")
        self.assertGreater(self.diag.counter("last_gap_s"), 0.5)
        self.send_commands(20)
        wait_for(lambda: self.status().last_seq == self.seq, 3.0, "commands flow again")


if __name__ == "__main__":
    rostest.rosrun("drone_ros", "link_sil", LinkStories)
