#!/usr/bin/env python3
"""One home for the whole stack, checked in a lockstep HiL flight (hil/test/home_agreement.test)
against the simulator's truth: the home the HA latched and publishes on /home, the home the
controller flies /way from (its diagnostics, before and after hp_supervisor restarts it), the
ground station's HOME_POSITION (asked for with MAV_CMD_GET_HOME_POSITION, as QGroundControl
does) and the origin of map, the tf tree's root (map -> odom -> base_link, from the vn200 node),
are the same point, and that point is where the aircraft was
parked. The truth's north/east use the simulator's own (Python) flat earth, independent of the
stack's C module on purpose."""
import bisect
import math
import sys
import unittest

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray
from drone_ros.msg import HilTruth, HomePosition
from pymavlink import mavutil
from tf2_msgs.msg import TFMessage

from flight_end import wait_for_the_simulator
from stack_testing.kept_messages import KeptMessages

FT_PER_M = 1.0 / 0.3048
# How far the HA's home may sit from the truth's parked position: three times the VN-200
# emulation's position error (hil/sensors.py: 1.0 m horizontal, 1.5 m vertical RMS), which the HA
# latches with the fix.
HOME_TOLERANCE_HORIZONTAL_M = 3.0
HOME_TOLERANCE_VERTICAL_M = 4.5
# The tf against the truth at the nearest step (10 ms apart at 100 Hz; the aircraft flies about
# 20 m/s), plus the INS's noise.
TF_TOLERANCE_M = 3.0


def horizontal_m(lat0, lon0, lat, lon):
    """Equirectangular distance on a sphere of the WGS84 mean radius: a check independent of
    the stack's WGS84 module, good to well under a metre over these few metres."""
    r = 6371008.8
    dn = math.radians(lat - lat0) * r
    de = math.radians(lon - lon0) * r * math.cos(math.radians(lat0))
    return math.hypot(dn, de)


class HomeAgreement(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("home_agreement_check")
        cls.out_dir = rospy.get_param("~out_dir")
        cls.crash_at_s = float(rospy.get_param("~crash_at_s"))
        cls.gs_port = int(rospy.get_param("~gs_udp_port"))
        cls.kept = KeptMessages()
        cls.truth = cls.kept.subscribe("/hil/truth", HilTruth, queue_size=100000)
        cls.homes = cls.kept.subscribe("/home", HomePosition, queue_size=100)
        cls.controller, cls.tfs = [], []
        rospy.Subscriber("/diagnostics", DiagnosticArray, cls._on_diagnostics, queue_size=1000)
        rospy.Subscriber("/tf", TFMessage, cls._on_tf, queue_size=100000)
        cls.home_position = None
        cls.sim_exit = wait_for_the_simulator(cls.out_dir, 800.0, poll_s=0.2, while_flying=cls._ask_once_airborne)

    @classmethod
    def _ask_once_airborne(cls):
        # The ground station is asked while the flight runs: the launch ends with the simulator.
        with cls.kept.lock:
            flying = bool(cls.truth) and cls.truth[-1].header.stamp.to_sec() > 5.0
        if flying and cls.home_position is None:
            cls.home_position = cls._ask_ground_station()

    @classmethod
    def _on_diagnostics(cls, msg):
        for s in msg.status:
            if "performance controller" in s.name:
                values = {kv.key: kv.value for kv in s.values}
                cls.kept.keep(cls.controller, (msg.header.stamp.to_sec(), values))

    @classmethod
    def _on_tf(cls, msg):
        for t in msg.transforms:
            if (t.header.frame_id, t.child_frame_id) == ("odom", "base_link"):
                cls.kept.keep(cls.tfs, t)

    @classmethod
    def _ask_ground_station(cls):
        """HOME_POSITION as a ground station gets it: MAV_CMD_GET_HOME_POSITION over UDP."""
        conn = mavutil.mavlink_connection("udpout:127.0.0.1:%d" % cls.gs_port, source_system=255,
                                          source_component=190, dialect="development")
        try:
            for _ in range(20):
                conn.mav.command_long_send(1, 1, mavutil.mavlink.MAV_CMD_GET_HOME_POSITION, 0, 0, 0, 0, 0, 0, 0, 0)
                m = conn.recv_match(type="HOME_POSITION", blocking=True, timeout=0.5)
                if m is not None:
                    return m
            return None
        finally:
            conn.close()

    def truth_home(self):
        """Where the aircraft was parked: the first truth sample, on the ground at time 0."""
        first = self.truth[0]
        self.assertTrue(first.on_ground)
        return first.latitude_deg, first.longitude_deg, first.altitude_msl_m

    def ha_home(self):
        self.assertTrue(self.homes, "no /home from the HA")
        return self.homes[-1]

    def test_1_the_flight_ran_to_its_end(self):
        self.assertEqual(0, self.sim_exit, "the simulator stopped early: see %s" % self.out_dir)

    def test_2_the_ha_latched_home_once_where_the_aircraft_was_parked(self):
        h = self.ha_home()
        lat, lon, alt = self.truth_home()
        self.assertLess(horizontal_m(lat, lon, h.latitude, h.longitude), HOME_TOLERANCE_HORIZONTAL_M)
        self.assertLess(abs(h.altitude - alt), HOME_TOLERANCE_VERTICAL_M)
        # Latched once and never moved: every /home the node relayed is the same point.
        self.assertEqual({1}, {m.seq for m in self.homes})
        self.assertEqual(1, len({(m.latitude, m.longitude, m.altitude) for m in self.homes}))

    def test_3_the_controller_flies_from_the_has_home_before_and_after_its_restart(self):
        h = self.ha_home()
        with_home = [(t, v) for t, v in self.controller if v.get("home_valid") == "True"]
        before = [v for t, v in with_home if t < self.crash_at_s]
        after = [v for t, v in with_home if t > self.crash_at_s]
        self.assertTrue(before, "no controller diagnostics with a home before the crash")
        self.assertTrue(after, "the restarted controller never reported a home")
        for v in before + after:
            self.assertAlmostEqual(h.latitude, float(v["home_lat_deg"]), places=8)
            self.assertAlmostEqual(h.longitude, float(v["home_lon_deg"]), places=8)
            self.assertAlmostEqual(h.altitude, float(v["home_alt_m"]), places=2)
        # It was a new process: its step counter started again from zero.
        steps = [int(v["steps"]) for t, v in self.controller if "steps" in v]  # not in a stale report
        self.assertTrue(any(b < a for a, b in zip(steps, steps[1:])), "the controller was never restarted")

    def test_4_the_ground_stations_home_position_is_the_has_home(self):
        self.assertIsNotNone(self.home_position, "no HOME_POSITION from microhard_gs")
        h = self.ha_home()
        self.assertEqual(round(h.latitude * 1e7), self.home_position.latitude)
        self.assertEqual(round(h.longitude * 1e7), self.home_position.longitude)
        self.assertEqual(round(h.altitude * 1000), self.home_position.altitude)

    def test_5_the_tf_puts_base_link_where_the_truth_is_from_home(self):
        # map -> odom is the identity (vn200_driver/README.md), so odom -> base_link is from home.
        self.assertTrue(self.tfs, "no tf odom -> base_link")
        stamps = [m.header.stamp.to_sec() for m in self.truth]
        airborne = [t for t in self.tfs if t.header.stamp.to_sec() > 5.0]
        self.assertGreater(len(airborne), 100)
        worst = 0.0
        for t in airborne[::10]:
            s = t.header.stamp.to_sec()
            i = bisect.bisect_left(stamps, s)
            i = min((k for k in (i - 1, i) if 0 <= k < len(stamps)), key=lambda k: abs(stamps[k] - s))
            tr = self.truth[i]
            east_m, north_m = t.transform.translation.x, t.transform.translation.y
            worst = max(worst, math.hypot(east_m - tr.east_ft / FT_PER_M, north_m - tr.north_ft / FT_PER_M))
        self.assertLess(worst, TF_TOLERANCE_M)


if __name__ == "__main__":
    rostest.rosrun("drone_ros", "home_agreement", HomeAgreement, sys.argv)
