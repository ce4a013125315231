"""The lockstep's count waits (hil/sim.py Waiter): a message that never reaches the simulator costs
one wait, not one per step for the rest of the flight. Under heavy load one HA report went out
before the simulator's subscription was live; the count stayed one short and every later step
waited out the full timeout (a 35 s flight that never ended)."""
import os
import threading
import time

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
from hil.sim import Waiter  # noqa: E402


def test_all_published_arrived_no_wait_and_nothing_lost():
    w = Waiter()
    for _ in range(3):
        w.hit("status")
    assert w.wait_published("status", 3, 5.0) == 0


def test_one_report_lost_before_the_subscription_is_waited_for_once_then_given_up():
    w = Waiter()
    w.hit("status")  # the first of three reports never arrived: two did
    w.hit("status")
    assert w.wait_published("status", 3, 0.2) == 1  # waited out once, one given up on
    for step in range(4, 40):  # every later step: its report arrives, and nothing is missing
        w.hit("status")
        # No time to wait at all: a step still counting the lost report would come up short.
        assert w.wait_published("status", step, 0.0) == 0, "step %d still misses the lost one" % step


def test_a_late_report_is_still_waited_for():
    w = Waiter()
    w.hit("pwm")
    threading.Timer(0.1, lambda: w.hit("pwm")).start()
    assert w.wait_published("pwm", 2, 5.0) == 0
    assert w.count("pwm") == 2


def test_counts_are_kept_per_topic():
    w = Waiter()
    w.hit("vn")
    assert w.wait_published("vn", 2, 0.05) == 1
    w.hit("status")
    assert w.wait_published("status", 1, 5.0) == 0



def test_a_silent_publisher_costs_one_timeout_not_one_per_message_until_it_speaks_again():
    """Campaign seed 26 #61: the vn200 node published nothing; each of its packets cost the
    simulator the full wait, and the flight timed out instead of ending with the HA flying."""
    w = Waiter()
    w.hit("vn")
    assert w.wait_published("vn", 2, 0.2) == 1  # waited out once: the node is silent
    assert w.silent("vn")
    start = time.monotonic()
    for expected in range(3, 50):  # each later packet is given up on at once
        assert w.wait_published("vn", expected, 0.2) == 1
    assert time.monotonic() - start < 0.2, "waited for a silent node"
    w.hit("vn")  # it speaks again
    assert not w.silent("vn")
    assert w.wait_published("vn", 50, 5.0) == 0
    threading.Timer(0.05, lambda: w.hit("vn")).start()
    assert w.wait_published("vn", 51, 5.0) == 0  # and is waited for as before
    assert w.count("vn") == 3
