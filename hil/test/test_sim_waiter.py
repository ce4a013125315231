"""The lockstep's count waits (hil/sim.py Waiter): a message that never reaches the simulator costs
one wait, not one per step for the rest of the flight. Under heavy load one HA report went out
before the simulator's subscription was live; the count stayed one short and every later step
waited out the full timeout (a 35 s flight that never ended)."""
import os
import sys
import threading

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
sys.path.insert(0, ROOT)
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
