"""The wait of the rostest stories (a helper, not a test): the link's (arduino_link/test) and the
markers' (report/test) drive a node and wait for what it must do."""
import time

import rospy


def wait_for(predicate, timeout_s, what):
    """Polls predicate until it holds; fails the story naming what never happened. A predicate may
    publish too (keep feeding the node until it answers): it runs every 20 ms."""
    deadline = time.time() + timeout_s
    while time.time() < deadline and not rospy.is_shutdown():
        if predicate():
            return
        time.sleep(0.02)
    raise AssertionError("timed out waiting for " + what)
