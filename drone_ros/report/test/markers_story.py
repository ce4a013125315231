#!/usr/bin/env python3
"""rostest story for flight_markers (not named test_*.py: pytest must not collect it): the node
from launch/view.launch is fed a mission, the HP flying east, a crash (the HA takes over with
REASON_NO_COMMAND) and the HA flying north; the markers must show it, in map, and the node must
publish no tf (the aircraft's tree map -> odom -> base_link is the vn200 node's).
~source: "truth" feeds /hil/truth (HiL), "data" feeds /data fixes (a real flight)."""
import math
import sys
import threading
import time
import unittest

import rospy
import rostest
from tf2_msgs.msg import TFMessage
from visualization_msgs.msg import Marker, MarkerArray

from drone_ros.msg import DecisionStatus, HilTruth, data as Data, way as Way
from stack_testing.story_wait import wait_for

FT = 0.3048
HOME = (38.9717, -95.2353, 250.0)
CEILING_FT = 400.0  # aircraft/DG808/limits.yaml state.ceiling_agl_ft, loaded by view.launch
HP_BLUE = (0x1f / 255.0, 0x77 / 255.0, 0xb4 / 255.0)
HA_RED = (0xd6 / 255.0, 0x27 / 255.0, 0x28 / 255.0)


class MarkersStory(unittest.TestCase):
    def setUp(self):
        self.lock = threading.Lock()
        self.arrays, self.transforms = [], []
        rospy.Subscriber("/flight_markers", MarkerArray, self._on_markers, queue_size=20)
        rospy.Subscriber("/tf", TFMessage, self._on_tf, queue_size=200)
        rospy.Subscriber("/tf_static", TFMessage, self._on_tf, queue_size=200)
        self.source = rospy.get_param("~source", "truth")
        self.truth = rospy.Publisher("/hil/truth", HilTruth, queue_size=100)
        self.data = rospy.Publisher("/data", Data, queue_size=100)
        self.status = rospy.Publisher("/decision_status", DecisionStatus, queue_size=10)
        self.way = rospy.Publisher("/way", Way, queue_size=1, latch=True)
        wait_for(lambda: self.status.get_num_connections() > 0 and self.way.get_num_connections() > 0
                 and (self.truth if self.source == "truth" else self.data).get_num_connections() > 0,
                 30.0, "flight_markers to subscribe")

    def _on_markers(self, m):
        with self.lock:
            self.arrays.append({marker.ns: marker for marker in m.markers})

    def _on_tf(self, m):
        with self.lock:
            self.transforms += list(m.transforms)

    def latest(self):
        with self.lock:
            return self.arrays[-1] if self.arrays else {}

    def last_track_point(self, predicate):
        track = self.latest().get("track")
        return track is not None and len(track.points) > 0 and predicate(track.points[-1])

    def decide(self, controller, reasons=0):
        self.status.publish(DecisionStatus(stamp=rospy.Time.now(), controller=controller, reasons=reasons))

    def fly_to(self, north_ft, east_ft, height_ft, heading_deg):
        if self.source == "truth":
            m = HilTruth(north_ft=north_ft, east_ft=east_ft, height_above_home_ft=height_ft,
                         heading_deg=heading_deg)
            m.header.stamp = rospy.Time.now()
            m.header.frame_id = "map"
            self.truth.publish(m)
        else:
            m = Data()
            m.header.stamp = rospy.Time.now()
            # WGS84 radii of curvature at home
            s = 1.0 - 6.69437999014e-3 * math.sin(math.radians(HOME[0])) ** 2
            r_meridian_m = 6378137.0 * (1.0 - 6.69437999014e-3) / s ** 1.5
            r_normal_m = 6378137.0 / math.sqrt(s)
            m.lla.x = HOME[0] + math.degrees(north_ft * FT / r_meridian_m)
            m.lla.y = HOME[1] + math.degrees(east_ft * FT / (r_normal_m * math.cos(math.radians(HOME[0]))))
            m.lla.z = HOME[2] + height_ft * FT
            m.angle.z = math.radians(heading_deg)
            self.data.publish(m)
        time.sleep(0.01)

    def test_track_mission_ceiling_reason_and_pose(self):
        plan = Way(north=[0.0] * 32, east=[0.0] * 32, height=[0.0] * 32, velocity=[0.0] * 32, fp=3)
        plan.north[:3] = [1000.0, 1000.0, 0.0]
        plan.east[:3] = [0.0, 1000.0, 1000.0]
        plan.height[:3] = [300.0] * 3
        self.way.publish(plan)

        # Topics are not ordered with each other: the node must know who flies before the first
        # position, or (correctly) that point is drawn as "unknown".
        wait_for(lambda: self.decide(DecisionStatus.CONTROLLER_HP) or (
            self.latest().get("decision") is not None
            and self.latest()["decision"].text == "HP"), 30.0, "the text HP")
        # Parked at home until the node has placed it (a real flight's first fix is home).
        wait_for(lambda: self.fly_to(0.0, 0.0, 0.0, 90.0) or self.last_track_point(lambda p: True), 30.0,
                 "a first track point")
        for i in range(60):  # HP: 600 ft east at 300 ft, heading east
            self.fly_to(0.0, 10.0 * i, 300.0, 90.0)
        # Topics are not ordered with each other: let the HP's stretch land before the switch.
        wait_for(lambda: self.last_track_point(lambda p: abs(p.x - 590.0 * FT) < 0.01), 30.0,
                 "the HP's stretch on the track")
        self.decide(DecisionStatus.CONTROLLER_HA, DecisionStatus.REASON_NO_COMMAND)
        wait_for(lambda: self.latest()["decision"].text == "HA: NO_COMMAND", 30.0, "the reason")
        for i in range(1, 41):  # HA: 400 ft north, heading north
            self.fly_to(10.0 * i, 590.0, 300.0, 0.0)

        wait_for(lambda: self.last_track_point(lambda p: abs(p.y - 400.0 * FT) < 0.01), 30.0,
                 "the track to reach the last position")
        markers = self.latest()

        track = markers["track"]
        self.assertEqual(Marker.LINE_STRIP, track.type)
        self.assertEqual("map", track.header.frame_id)
        self.assertEqual(len(track.points), len(track.colors))
        colours = [(round(c.r, 3), round(c.g, 3), round(c.b, 3)) for c in track.colors]
        blue = tuple(round(v, 3) for v in HP_BLUE)
        red = tuple(round(v, 3) for v in HA_RED)
        self.assertEqual(blue, colours[0])
        self.assertEqual(red, colours[-1])
        first_red = colours.index(red)
        self.assertTrue(all(c == blue for c in colours[:first_red]))
        self.assertTrue(all(c == red for c in colours[first_red:]))
        # The HP's stretch runs east (ENU x) and the HA's north (ENU y), in metres, at 300 ft.
        self.assertAlmostEqual(590.0 * FT, track.points[first_red].x, delta=0.5)
        self.assertAlmostEqual(590.0 * FT, track.points[first_red - 1].x, delta=3.1)
        self.assertEqual((0.0, 0.0, 0.0), (track.points[0].x, track.points[0].y, track.points[0].z))
        airborne = [p for p in track.points if p.z > 1.0]
        self.assertEqual(airborne, track.points[len(track.points) - len(airborne):])
        for p in airborne:
            self.assertAlmostEqual(300.0 * FT, p.z, delta=0.2)

        waypoints = markers["waypoints"]
        self.assertEqual(Marker.SPHERE_LIST, waypoints.type)
        self.assertEqual([(0.0, 1000.0 * FT), (1000.0 * FT, 1000.0 * FT), (1000.0 * FT, 0.0)],
                         [(round(p.x, 6), round(p.y, 6)) for p in waypoints.points])

        ceiling = markers["ceiling"]
        self.assertEqual(Marker.CUBE, ceiling.type)
        self.assertAlmostEqual(CEILING_FT * FT, ceiling.pose.position.z, places=3)
        self.assertGreaterEqual(ceiling.scale.x, 1000.0 * FT)
        self.assertGreaterEqual(ceiling.scale.y, 1000.0 * FT)
        self.assertLess(ceiling.scale.z, 1.0)

        # The text rides 30 m above where the aircraft is, in map (ENU metres from home).
        decision = markers["decision"]
        self.assertEqual(Marker.TEXT_VIEW_FACING, decision.type)
        self.assertEqual("map", decision.header.frame_id)
        self.assertAlmostEqual(590.0 * FT, decision.pose.position.x, delta=0.5)
        self.assertAlmostEqual(400.0 * FT, decision.pose.position.y, delta=0.5)
        self.assertAlmostEqual(300.0 * FT + 30.0, decision.pose.position.z, delta=0.2)

        # One tf tree: nothing here broadcasts (no vn200 node runs), so any transform is this
        # node's second, disconnected tree.
        with self.lock:
            self.assertEqual([], [(t.header.frame_id, t.child_frame_id) for t in self.transforms])


if __name__ == "__main__":
    rospy.init_node("markers_story", anonymous=True)
    rostest.rosrun("drone_ros", "markers_" + rospy.get_param("~source", "truth"), MarkersStory, sys.argv)
