#!/usr/bin/env python3
"""Wire compatibility with a stock rosserial_arduino sketch: the real `arduino` node against
roslib_device.py (ros_lib's NodeHandle restated from the protocol, nothing shared with our own
device code) on a pseudo-terminal. Run by roslib_compat.test."""
import struct
import unittest

import rospy
import rostest
from rosgraph_msgs.msg import Log
from roscpp.srv import SetLoggerLevel
from std_msgs.msg import Bool, Float32, Int32, String

from roslib_device import RunningSketch, ser_string  # noqa: E402
from link_diagnostics import LinkDiagnostics  # noqa: E402
from stack_testing.story_wait import wait_for  # noqa: E402
from stack_testing.kept_messages import KeptMessages  # noqa: E402


class RoslibSketchStories(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("roslib_story")
        cls.kept = KeptMessages()
        cls.chatter = cls.kept.subscribe("chatter", String, queue_size=100, value=lambda m: m.data)
        cls.battery = cls.kept.subscribe("battery_v", Float32, queue_size=100, value=lambda m: m.data)
        cls.rosout = []
        rospy.Subscriber("/rosout", Log, cls._log, queue_size=1000)
        cls.diag = LinkDiagnostics()
        cls.led = rospy.Publisher("led", Bool, queue_size=10)
        cls.setpoint = rospy.Publisher("setpoint", Int32, queue_size=10)
        # The node forwards a ROSDEBUG device log with ROS_DEBUG, which rosout only carries once
        # the node's logger is at debug; set it before the sketch logs anything.
        rospy.wait_for_service("/arduino/set_logger_level", timeout=30.0)
        rospy.ServiceProxy("/arduino/set_logger_level", SetLoggerLevel)("ros.drone_ros", "debug")
        cls.rig = RunningSketch(rospy.get_param("~node_port"))
        cls.device, cls.sketch = cls.rig.device, cls.rig.sketch

    @classmethod
    def tearDownClass(cls):
        cls.rig.stop()

    @classmethod
    def _log(cls, m):
        if m.name == "/arduino":
            cls.kept.keep(cls.rosout, (m.level, m.msg))

    def events(self, kind):
        return self.rig.events(kind)

    def test_01_the_node_asks_for_topics_with_the_documented_bytes_and_takes_the_sketchs(self):
        wait_for(lambda: self.events("negotiated"), 20.0, "the sketch to negotiate its topics")
        self.assertEqual(self.events("topic_request")[0], b"", "the topic request is an empty frame on topic 0")
        # ros_lib numbering: subscribers from 100, publishers from 100 + MAX_SUBSCRIBERS.
        self.assertEqual(self.events("negotiated")[0], [125, 126, 100, 101])
        wait_for(lambda: ["/chatter", "std_msgs/String"] in rospy.get_published_topics()
                 and ["/battery_v", "std_msgs/Float32"] in rospy.get_published_topics(), 10.0,
                 "the node to advertise the sketch's publishers with their types")
        wait_for(lambda: self.led.get_num_connections() > 0 and self.setpoint.get_num_connections() > 0, 10.0,
                 "the node to subscribe for the sketch's subscribers")

    def test_02_the_sketchs_topics_carry_its_values(self):
        wait_for(lambda: len(self.chatter) >= 5 and len(self.battery) >= 5, 20.0, "the sketch's messages")
        with self.kept.lock:
            self.assertTrue(all(s.startswith("hello from ros_lib ") for s in self.chatter), self.chatter[:3])
            counts = [int(s.rsplit(" ", 1)[1]) for s in self.chatter]
            self.assertEqual(counts, sorted(counts), "in order")
            self.assertTrue(all(v == 11.5 for v in self.battery))

    def test_03_messages_on_the_sketchs_subscriptions_reach_it_byte_exact(self):
        wait_for(lambda: self.led.get_num_connections() > 0 and self.setpoint.get_num_connections() > 0, 20.0,
                 "the node subscribed")
        self.setpoint.publish(Int32(-123456))
        self.led.publish(Bool(True))
        wait_for(lambda: ("setpoint", struct.pack("<i", -123456)) in self.events("received"), 5.0,
                 "std_msgs/Int32 -123456 as 4 little-endian bytes on id 101")
        wait_for(lambda: ("led", b"\x01") in self.events("received"), 5.0, "std_msgs/Bool true as one byte on id 100")
        self.assertEqual(self.events("bad_checksum"), [], "every frame from the node checks out")
        self.assertEqual(self.events("unknown_topic"), [], "the node sent on no id the sketch did not announce")

    def test_04_time_requests_before_and_after_negotiation_get_ros_time(self):
        # ros_lib asks once as it negotiates (just before its TopicInfos), then every 2.5 s.
        wait_for(lambda: len(self.events("time_reply")) >= 2, 10.0, "two time replies")
        with self.device.lock:
            order = [k for k, _ in self.device.events if k in ("time_request", "negotiated")]
        first = order.index("negotiated")
        self.assertIn("time_request", order[:first], "a time request before the TopicInfos")
        self.assertIn("time_request", order[first + 1:], "and again once configured")
        sec, nsec = self.device.now()
        self.assertLess(abs(sec + nsec * 1e-9 - rospy.Time.now().to_sec()), 1.0,
                        "the sketch's clock follows ROS time after syncing")
        self.assertTrue(all(s > 0 for s, _ in self.events("time_reply")))

    def test_05_int_float_and_string_parameters_are_answered(self):
        wait_for(lambda: len(self.events("param")) == 3, 20.0, "the sketch's three getParam calls")
        got = {name: values for name, _, values in self.events("param")}
        self.assertEqual(got["device/rate_hz"], [50])
        self.assertEqual(len(got["device/gain"]), 1)
        self.assertAlmostEqual(got["device/gain"][0], 0.25, places=6)
        self.assertEqual(got["device/label"], ["left wing"])

    def test_06_logs_reach_rosout_at_their_levels(self):
        expected = {"debug": Log.DEBUG, "info": Log.INFO, "warn": Log.WARN, "error": Log.ERROR, "fatal": Log.FATAL}

        def seen():
            with self.kept.lock:
                return {msg.rsplit(" ", 1)[1]: level for level, msg in self.rosout
                        if msg.startswith("[HA] roslib_device ")}

        wait_for(lambda: len(seen()) == len(expected), 20.0, "a device log at every level on /rosout")
        self.assertEqual(seen(), expected)

    def test_07_a_malformed_message_of_a_known_type_is_counted_not_published(self):
        wait_for(lambda: len(self.chatter) > 0 and self.diag.heard(), 20.0, "the link up and diagnostics")
        before = self.diag.counter("bad_payload")
        # A std_msgs/String whose length prefix claims more bytes than the frame holds.
        self.device.publish(self.sketch.chatter.id, struct.pack("<I", 100) + b"short")
        self.device.publish(self.sketch.chatter.id, ser_string("hello from ros_lib after the bad one"))
        wait_for(lambda: self.diag.counter("bad_payload") > before, 5.0, "the bad payload counted")
        wait_for(lambda: "hello from ros_lib after the bad one" in self.chatter, 5.0, "the next message published")
        with self.kept.lock:
            self.assertFalse(any("short" in s for s in self.chatter))


if __name__ == "__main__":
    rostest.rosrun("drone_ros", "roslib_compat", RoslibSketchStories)
