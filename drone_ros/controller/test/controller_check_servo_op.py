#!/usr/bin/env python3
"""rostest: controller_DG808 publishes /servo_op at the configured rate (median period of the
command stamps), with seq increasing by exactly one, valid CRC-32 and, fed fresh sensors,
sensor_links_healthy; /data and /to_hil are published alongside. With ~expect_sensor_loss the
feeder goes quiet part-way: the commands keep coming on the controller's own clock, now flagged
sensor_links_healthy false. With ~exercise_restart the HA's restart request (/decision_status)
re-initializes the GNC: its estimator starts over (not converged) and the sequence runs on."""
import statistics
import struct
import sys
import threading
import unittest
import zlib

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray
from drone_ros.msg import DecisionStatus, ServoCommand, data, hil_data

COLLECT_S = 3.0


def crc_of(m):
    fields = struct.pack("<IIIffffffBB", m.seq, m.stamp.secs, m.stamp.nsecs, m.throttle,
                         m.elevator_deg, m.aileron_deg, m.rudder_deg, m.alpha_est_deg,
                         m.beta_est_deg, int(m.estimator_converged), int(m.sensor_links_healthy))
    return zlib.crc32(fields) & 0xFFFFFFFF


class ServoOpRate(unittest.TestCase):
    def test_servo_op_at_configured_rate_with_sequence_and_crc(self):
        expected_hz = float(rospy.get_param("~expected_rate_hz"))
        msgs, other = [], {"data": 0, "hil": 0}
        lock = threading.Lock()
        done = threading.Event()

        def on_cmd(m):
            with lock:
                msgs.append(m)
                if len(msgs) > 1 and (m.stamp - msgs[0].stamp).to_sec() >= COLLECT_S:
                    done.set()

        rates = []
        rospy.Subscriber("/diagnostics", DiagnosticArray, lambda arr: rates.extend(
            st for st in arr.status if "/servo_op rate" in st.name))
        rospy.Subscriber("/servo_op", ServoCommand, on_cmd, queue_size=1000)
        rospy.Subscriber("/data", data, lambda _m: other.__setitem__("data", other["data"] + 1))
        rospy.Subscriber("/to_hil", hil_data, lambda _m: other.__setitem__("hil", other["hil"] + 1))
        # Let the feeder's sensors arrive before judging their health.
        self.assertTrue(done.wait(25.0), "no 3 s of /servo_op within 25 s")
        with lock:
            got = list(msgs)
        for a, b in zip(got, got[1:]):
            self.assertEqual(b.seq, a.seq + 1, "sequence jumped from %d to %d" % (a.seq, b.seq))
        for m in got:
            self.assertEqual(m.crc32, crc_of(m), "bad CRC on seq %d" % m.seq)
        periods = [(b.stamp - a.stamp).to_sec() for a, b in zip(got, got[1:])]
        median = statistics.median(periods)
        self.assertAlmostEqual(median, 1.0 / expected_hz, delta=0.2 / expected_hz,
                               msg="median period %.4f s" % median)
        self.assertTrue(got[-1].sensor_links_healthy, "fresh sensors reported unhealthy")
        # The node's own "/servo_op rate" diagnostic says the same: the configured rate, met.
        deadline = rospy.Time.now() + rospy.Duration(5.0)
        while not any(st.level == st.OK for st in rates) and rospy.Time.now() < deadline:
            rospy.sleep(0.1)
        met = [st for st in rates if st.level == st.OK]
        self.assertTrue(met, "the /servo_op rate never reported met: %s" % [st.message for st in rates])
        values = {kv.key: kv.value for kv in met[-1].values}
        self.assertAlmostEqual(expected_hz, float(values["Target frequency (Hz)"]), places=3)
        self.assertAlmostEqual(expected_hz, float(values["Actual frequency (Hz)"]), delta=0.1 * expected_hz)
        self.assertGreater(other["data"], 0)
        self.assertGreater(other["hil"], 0)
        if rospy.get_param("~exercise_restart", False):
            self.restart_reinitializes_the_gnc(msgs, lock)
        if rospy.get_param("~expect_sensor_loss", False):
            deadline = rospy.get_time() + 20.0
            lost_at = None
            while lost_at is None and rospy.get_time() < deadline:
                with lock:
                    lost_at = next((i for i, m in enumerate(msgs) if not m.sensor_links_healthy
                                    and i > len(got)), None)
                rospy.sleep(0.1)
            self.assertIsNotNone(lost_at, "sensors stopped but the command still says healthy")
            rospy.sleep(1.0)
            with lock:
                after = list(msgs[lost_at:])
            self.assertGreater(len(after), 0.5 * expected_hz, "commands stopped with the sensors")
            for a, b in zip(after, after[1:]):
                self.assertEqual(b.seq, a.seq + 1)
                self.assertFalse(b.sensor_links_healthy)
                self.assertEqual(b.crc32, crc_of(b))

    def restart_reinitializes_the_gnc(self, msgs, lock):
        with lock:
            self.assertTrue(msgs[-1].estimator_converged, "estimator not converged on steady flight")
            start = len(msgs)
        pub = rospy.Publisher("/decision_status", DecisionStatus, queue_size=1, latch=True)
        request = DecisionStatus(controller=DecisionStatus.CONTROLLER_HA, restart_requested=True)
        request.stamp = rospy.Time.now()
        pub.publish(request)
        deadline = rospy.get_time() + 10.0
        restarted = None
        while restarted is None and rospy.get_time() < deadline:
            rospy.sleep(0.1)
            with lock:
                restarted = next((i for i in range(start, len(msgs))
                                  if not msgs[i].estimator_converged), None)
        self.assertIsNotNone(restarted, "restart request left the estimator untouched")
        rospy.sleep(2.0)
        with lock:
            after = list(msgs[start:])
        for a, b in zip(after, after[1:]):
            self.assertEqual(b.seq, a.seq + 1, "restart broke the sequence")
        self.assertTrue(after[-1].estimator_converged, "estimator did not converge again")


if __name__ == "__main__":
    rospy.init_node("check_servo_op", anonymous=True)
    rostest.rosrun("drone_ros", "servo_op_rate", ServoOpRate, sys.argv)
