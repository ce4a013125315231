#!/usr/bin/env python3
"""rostest: hp_supervisor restarts controller_DG808 on the HA's request and reports it on
/diagnostics (not named test_*.py: pytest must not collect it)."""
import sys
import threading
import unittest

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from drone_ros.msg import DecisionStatus, ServoCommand

NAME = "hp_supervisor: /controller_DG808"


class SupervisorRestart(unittest.TestCase):
    def test_a_restart_request_restarts_the_controller_and_the_diagnostics_say_how(self):
        lock = threading.Lock()
        statuses, commands = [], []

        def on_diag(arr):
            with lock:
                statuses.extend(st for st in arr.status if st.name == NAME)

        def on_cmd(m):
            with lock:
                commands.append(m)

        def latest():
            with lock:
                return (statuses[-1], {kv.key: kv.value for kv in statuses[-1].values}) if statuses else (None, {})

        def wait(pred, timeout_s, what):
            deadline = rospy.Time.now() + rospy.Duration(timeout_s)
            while not pred() and rospy.Time.now() < deadline and not rospy.is_shutdown():
                rospy.sleep(0.1)
            self.assertTrue(pred(), what)

        rospy.Subscriber("/diagnostics", DiagnosticArray, on_diag)
        rospy.Subscriber("/servo_op", ServoCommand, on_cmd)
        status_pub = rospy.Publisher("/decision_status", DecisionStatus, queue_size=10)
        wait(lambda: latest()[0] is not None and len(commands) > 20, 20.0, "no supervisor status or no commands")
        st, values = latest()
        self.assertEqual(DiagnosticStatus.OK, st.level, st.message)
        self.assertEqual("0", values["restarts"])
        wait(lambda: status_pub.get_num_connections() > 0, 10.0, "the supervisor does not listen")
        for requested in (False, True, True):  # one rising edge
            status_pub.publish(DecisionStatus(controller=DecisionStatus.CONTROLLER_HA,
                                              restart_requested=requested))
            rospy.sleep(0.1)
        wait(lambda: latest()[1].get("restarts") == "1" and latest()[0].level == DiagnosticStatus.OK, 15.0,
             "no restart reported: %s" % (latest(),))
        st, values = latest()
        self.assertEqual("SIGTERM", values["last stop"])
        self.assertTrue(values["started pid"].isdigit(), values)
        # The new controller flies: its commands count from seq 0 again.
        def seq_restarted():
            with lock:
                return any(b.seq < a.seq for a, b in zip(commands, commands[1:]))
        wait(seq_restarted, 15.0, "no command from the new controller")

if __name__ == "__main__":
    rospy.init_node("check_supervisor")
    rostest.rosrun("drone_ros", "supervisor_restart", SupervisorRestart, sys.argv)
