"""What a rostest check keeps of its subscriptions: rospy delivers each topic on a thread of its
own while the test reads, so the lists are filled and read under one lock."""
import threading

import rospy


class KeptMessages:
    def __init__(self):
        self.lock = threading.Lock()

    def keep(self, into, value):
        with self.lock:
            into.append(value)

    def subscribe(self, topic, msg_type, queue_size, value=lambda m: m):
        """A list that keeps value(m) of every message m on topic, from now on."""
        into = []
        rospy.Subscriber(topic, msg_type, lambda m: self.keep(into, value(m)), queue_size=queue_size)
        return into
