#!/usr/bin/env python3
"""A TopicInfo lost on the wire: the real `arduino` node against roslib_device.py whose first
answer to a topic request carries its publishers' TopicInfos but loses its subscribers' (a full
USB buffer drops bytes; CI's QEMU board lost exactly these two, and the HA never got a command).
The publishers bring the link up; the node must still ask again, learn of the subscribers and
forward what ROS publishes on them. Run by roslib_lossy_negotiation.test."""
import struct
import unittest

import rospy
import rostest
from std_msgs.msg import Bool, Int32, String

from roslib_device import RunningSketch  # noqa: E402
from link_diagnostics import LinkDiagnostics  # noqa: E402
from stack_testing.story_wait import wait_for  # noqa: E402


class LostSubscriberInfos(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("roslib_lossy_story")
        cls.chatter = []
        rospy.Subscriber("chatter", String, lambda m: cls.chatter.append(m.data), queue_size=100)
        cls.diag = LinkDiagnostics()
        cls.led = rospy.Publisher("led", Bool, queue_size=10)
        cls.setpoint = rospy.Publisher("setpoint", Int32, queue_size=10)
        cls.rig = RunningSketch(rospy.get_param("~node_port"), lose_subscriber_infos_once=True)
        cls.device, cls.sketch = cls.rig.device, cls.rig.sketch

    @classmethod
    def tearDownClass(cls):
        cls.rig.stop()

    def events(self, kind):
        return self.rig.events(kind)

    def test_the_node_asks_again_and_forwards_to_the_subscribers_the_first_answer_lost(self):
        wait_for(lambda: len(self.chatter) >= 3, 20.0, "the link up on the publishers alone")
        self.assertEqual(self.events("negotiated")[0], [125, 126], "the first answer lost the subscribers")
        wait_for(lambda: self.led.get_num_connections() > 0 and self.setpoint.get_num_connections() > 0, 10.0,
                 "the node to ask for topics again and subscribe for the sketch's subscribers")
        self.assertGreaterEqual(len(self.events("topic_request")), 2)
        self.assertEqual(self.events("negotiated")[1], [125, 126, 100, 101])
        self.setpoint.publish(Int32(4242))
        self.led.publish(Bool(True))
        wait_for(lambda: ("setpoint", struct.pack("<i", 4242)) in self.events("received"), 5.0,
                 "the setpoint reaching the sketch")
        wait_for(lambda: ("led", b"\x01") in self.events("received"), 5.0, "the led reaching the sketch")
        wait_for(lambda: self.diag.counter("topic_confirmations") >= 1, 10.0,
                 "the node's diagnostics to count the confirming request")

    def test_a_whole_answer_ends_the_confirmations(self):
        wait_for(lambda: self.led.get_num_connections() > 0, 20.0, "the node subscribed")
        wait_for(lambda: self.diag.counter("topic_confirmations") >= 2, 10.0, "the answer with nothing new asked")
        settled = len(self.events("topic_request"))
        rospy.sleep(2.5)  # over twice the node's topic_request_period_s (1 s)
        self.assertEqual(len(self.events("topic_request")), settled, "no topic request once nothing new came")


if __name__ == "__main__":
    rostest.rosrun("drone_ros", "roslib_lossy_negotiation", LostSubscriberInfos)
