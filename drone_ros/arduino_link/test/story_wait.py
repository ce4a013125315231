"""What the link rostests share (not named test_*.py: pytest must not collect it)."""
import time

import rospy


def wait_for(predicate, timeout_s, what):
    """Polls predicate until it holds; fails the story naming what never happened."""
    deadline = time.time() + timeout_s
    while time.time() < deadline and not rospy.is_shutdown():
        if predicate():
            return
        time.sleep(0.02)
    raise AssertionError("timed out waiting for " + what)
