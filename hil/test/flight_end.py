"""What the rostest checks of a lockstep flight share (not named test_*.py: pytest must not
collect it)."""
import os
import time

import rospy


def wait_for_the_simulator(out_dir, timeout_s, poll_s, while_flying=lambda: None):
    """Waits for the simulator's exit code in out_dir/done (written as it ends; the launch ends
    with it), calling while_flying at each poll until then, and returns that code."""
    done = os.path.join(out_dir, "done")
    deadline = time.monotonic() + timeout_s
    while not os.path.exists(done) and time.monotonic() < deadline and not rospy.is_shutdown():
        while_flying()
        time.sleep(poll_s)
    time.sleep(1.0)  # the last messages
    with open(done) as f:
        return int(f.read().strip())
