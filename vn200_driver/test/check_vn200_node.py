#!/usr/bin/env python3
"""rostest checks for the vn200 node (not named test_*.py: pytest must not collect it).

live:   against fake_vn200.py on a pty that unplugs itself 4 s after each connect.
replay: against the recorded capture in test/data (100 packets of the fake's flight).
The expected values are the fake sensor's simulated flight (see scripts/fake_vn200.py).
"""
import math
import sys
import threading
import time
import unittest

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray
from geometry_msgs.msg import Point, Twist, TwistStamped
from nav_msgs.msg import Odometry
from sensor_msgs.msg import FluidPressure, Imu, MagneticField, NavSatFix, Temperature
from tf2_msgs.msg import TFMessage

from drone_ros.msg import ins as Ins

PITCH_RAD, ROLL_RAD = math.radians(2.0), math.radians(-3.0)
LAT0_DEG, LON0_DEG, ALT0_M = 45.4642, 9.1900, 150.0


class Recorder:
    def __init__(self):
        self.lock = threading.Lock()
        self.msgs = {}
        self.times = {}

    def sub(self, topic, cls):
        rospy.Subscriber(topic, cls, self._cb, callback_args=topic, queue_size=200)

    def _cb(self, msg, topic):
        with self.lock:
            self.msgs.setdefault(topic, []).append(msg)
            self.times.setdefault(topic, []).append(time.monotonic())

    def get(self, topic):
        with self.lock:
            return list(self.msgs.get(topic, []))

    def wait_for(self, pred, timeout_s):
        deadline = time.monotonic() + timeout_s
        while time.monotonic() < deadline and not rospy.is_shutdown():
            if pred():
                return True
            time.sleep(0.05)
        return pred()


def make_recorder():
    r = Recorder()
    for topic, cls in [("/ins", Ins), ("/attitude", Point), ("/gps_position", NavSatFix),
                       ("/gps_velocity", Twist), ("/imu_PQR_acceleration", Imu),
                       ("/vn200/imu/data", Imu), ("/vn200/fix", NavSatFix),
                       ("/vn200/velocity", TwistStamped), ("/vn200/imu/mag", MagneticField),
                       ("/vn200/pressure", FluidPressure), ("/vn200/temperature", Temperature),
                       ("/odom", Odometry), ("/diagnostics", DiagnosticArray), ("/tf", TFMessage),
                       ("/tf_static", TFMessage)]:
        r.sub(topic, cls)
    return r


def rate_statuses(rec):
    """Every "/ins rate" status the node has published, oldest first."""
    return [st for arr in rec.get("/diagnostics") for st in arr.status if "/ins rate" in st.name]


def diag_values(rec):
    for arr in reversed(rec.get("/diagnostics")):
        for st in arr.status:
            if "VN-200 link" in st.name:
                return {kv.key: kv.value for kv in st.values}, st
    return None, None


class ValueChecks:
    """Assertions on what one packet of the fake's flight must look like on each topic."""

    def check_values(self, rec):
        att = rec.get("/attitude")[-1]
        self.assertAlmostEqual(ROLL_RAD, att.x, places=4)
        self.assertAlmostEqual(PITCH_RAD, att.y, places=4)
        self.assertTrue(0 <= att.z < 2 * math.pi)
        ins = rec.get("/ins")[-1]
        self.assertEqual(1, ins.usbstatus)
        self.assertEqual(9, ins.num_sats)
        self.assertEqual(3, ins.gps_fix)
        self.assertEqual(2170, ins.week)
        self.assertEqual(2, ins.ins_status & 0x3)
        self.assertTrue(345600 <= ins.time < 604800)
        fix = rec.get("/gps_position")[-1]
        self.assertAlmostEqual(LAT0_DEG, fix.latitude, places=2)
        self.assertAlmostEqual(LON0_DEG, fix.longitude, places=6)
        self.assertAlmostEqual(ALT0_M, fix.altitude, places=3)
        rep_fix = rec.get("/vn200/fix")[-1]
        self.assertAlmostEqual(4.0, rep_fix.position_covariance[0], places=4)  # INS PosU 2 m
        self.assertEqual(NavSatFix.COVARIANCE_TYPE_APPROXIMATED, rep_fix.position_covariance_type)
        vel = rec.get("/gps_velocity")[-1]
        self.assertAlmostEqual(20.0, vel.linear.x, places=4)  # north
        enu = rec.get("/vn200/velocity")[-1]
        self.assertAlmostEqual(1.0, enu.twist.linear.x, places=4)  # east
        self.assertAlmostEqual(20.0, enu.twist.linear.y, places=4)  # north
        self.assertAlmostEqual(0.5, enu.twist.linear.z, places=4)  # up = -down
        pqr = rec.get("/imu_PQR_acceleration")[-1]
        self.assertAlmostEqual(-9.81, pqr.linear_acceleration.z, places=4)  # sensor axes, z down
        self.assertAlmostEqual(math.radians(5.0), pqr.angular_velocity.z, places=5)
        imu = rec.get("/vn200/imu/data")[-1]
        self.assertAlmostEqual(9.81, imu.linear_acceleration.z, places=4)  # REP-103, z up
        self.assertAlmostEqual(-math.radians(5.0), imu.angular_velocity.z, places=5)
        q = imu.orientation
        self.assertAlmostEqual(1.0, q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w, places=5)
        self.assertGreater(imu.orientation_covariance[8], 0.0)
        self.assertAlmostEqual(99800.0, rec.get("/vn200/pressure")[-1].fluid_pressure, delta=1.0)
        self.assertAlmostEqual(24.5, rec.get("/vn200/temperature")[-1].temperature, places=4)
        self.assertAlmostEqual(0.43e-4, -rec.get("/vn200/imu/mag")[-1].magnetic_field.z,
                               places=8)
        self.check_tf(rec)

    def check_tf(self, rec):
        """REP-105, one tree: map -> odom (identity) and base_link -> vn200 (the mount, ~mount) on
        /tf_static, odom -> base_link each solution on /tf. Composed, map -> vn200 must be the
        sensor's INS solution: the fake flies north from home (/home, published at its start) at
        constant height, so the sensor moves along +y of map, turned as ~imu/data says at the
        same stamp. odom (nav_msgs/Odometry) is the same pose, and its body-frame twist, turned
        back into map with the lever arm's swing added, the sensor's ENU velocity."""
        def base_tfs():
            return [t for m in rec.get("/tf") for t in m.transforms if t.child_frame_id == "base_link"]

        # /tf, odom and ~imu/data reach us on separate connections: under load any may lag the
        # others, so wait for a transform whose imu and odom samples have arrived too.
        def stamps(topic):
            return {m.header.stamp for m in rec.get(topic)}

        def matched():
            both = stamps("/vn200/imu/data") & stamps("/odom")
            return [t for t in base_tfs() if t.header.stamp in both]

        self.assertTrue(rec.wait_for(base_tfs, 5.0), "no tf odom -> base_link")
        self.assertTrue(rec.wait_for(matched, 5.0), "no odom and ~imu/data at a tf's stamp")
        last = matched()[-1]
        self.assertEqual("odom", last.header.frame_id)
        statics = {(t.header.frame_id, t.child_frame_id): t
                   for m in rec.get("/tf_static") for t in m.transforms}
        self.assertEqual({("map", "odom"), ("base_link", "vn200"), ("vn200", "vn200_frd")},
                         set(statics))
        identity = statics[("map", "odom")].transform
        self.assertEqual((0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0), vec(identity.translation) + quat(identity.rotation))
        self.assertEqual((1.0, 0.0, 0.0, 0.0), quat(statics[("vn200", "vn200_frd")].transform.rotation))
        mount = statics[("base_link", "vn200")].transform
        # The mount as given (FRD metres, yaw only in these tests) in REP-103 axes: y and z and
        # the yaw change sign.
        given = rospy.get_param("/vn200/mount", {})
        x_m, y_m, z_m = (float(given.get(k, 0.0)) for k in ("x_m", "y_m", "z_m"))
        half_yaw = math.radians(float(given.get("yaw_deg", 0.0))) / 2.0
        for a, b in zip((x_m, -y_m, -z_m, 0.0, 0.0, -math.sin(half_yaw), math.cos(half_yaw)),
                        vec(mount.translation) + quat(mount.rotation)):
            self.assertAlmostEqual(a, b, places=6)

        q_base, p_base = quat(last.transform.rotation), vec(last.transform.translation)
        arm = qrot(q_base, vec(mount.translation))
        sensor = tuple(p + a for p, a in zip(p_base, arm))
        self.assertAlmostEqual(0.0, sensor[0], places=2)
        self.assertAlmostEqual(0.0, sensor[2], places=2)
        self.assertGreater(sensor[1], 0.1)
        q_sensor = qmul(q_base, quat(mount.rotation))
        imu = [m for m in rec.get("/vn200/imu/data") if m.header.stamp == last.header.stamp][-1]
        sign = 1.0 if q_sensor[3] * imu.orientation.w >= 0 else -1.0
        for a, b in zip(quat(imu.orientation), q_sensor):
            self.assertAlmostEqual(a, sign * b, places=5)

        odom = [m for m in rec.get("/odom") if m.header.stamp == last.header.stamp][-1]
        self.assertEqual(("odom", "base_link"), (odom.header.frame_id, odom.child_frame_id))
        for a, b in zip(vec(odom.pose.pose.position) + quat(odom.pose.pose.orientation),
                        p_base + q_base):
            self.assertAlmostEqual(a, b, places=6)
        self.assertAlmostEqual(4.0, odom.pose.covariance[0], places=4)  # INS PosU 2 m
        self.assertGreater(odom.pose.covariance[35], 0.0)  # yaw, from the attitude uncertainty
        self.assertGreater(odom.twist.covariance[35], 0.0)  # rates: the datasheet's gyro noise
        w, r = vec(odom.twist.twist.angular), vec(mount.translation)
        swing = (w[1] * r[2] - w[2] * r[1], w[2] * r[0] - w[0] * r[2], w[0] * r[1] - w[1] * r[0])
        v_enu = qrot(q_base, tuple(v + s for v, s in zip(vec(odom.twist.twist.linear), swing)))
        for a, b in zip((1.0, 20.0, 0.5), v_enu):  # east, north, up
            self.assertAlmostEqual(a, b, places=3)


def vec(v):
    return (v.x, v.y, v.z)


def quat(q):
    return (q.x, q.y, q.z, q.w)


def qmul(a, b):
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (aw * bx + ax * bw + ay * bz - az * by, aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw, aw * bw - ax * bx - ay * by - az * bz)


def qrot(q, v):
    x, y, z, _ = qmul(qmul(q, v + (0.0,)), (-q[0], -q[1], -q[2], q[3]))
    return (x, y, z)


class LiveSensor(unittest.TestCase, ValueChecks):
    def test_configures_publishes_and_survives_unplug(self):
        rec = make_recorder()
        self.assertTrue(rec.wait_for(lambda: len(rec.get("/attitude")) >= 20, 15.0),
                        "no attitude stream: the node did not configure the fake sensor")
        # Every topic check_values reads, not only the 50 Hz ones: the GPS topics come at a lower
        # rate, and 20 attitude messages can arrive before the first of them (fresh-clone make test).
        self.assertTrue(rec.wait_for(lambda: all(rec.get(t) for t in [
            "/vn200/imu/mag", "/vn200/pressure", "/vn200/temperature", "/vn200/velocity",
            "/gps_position", "/gps_velocity", "/imu_PQR_acceleration", "/ins", "/vn200/fix",
            "/vn200/imu/data"]), 3.0))
        self.check_values(rec)
        # Stamps come from the sensor clock: evenly spaced at 20 ms, close to now.
        stamps = [m.header.stamp.to_sec() for m in rec.get("/vn200/imu/data")[-15:]]
        gaps = [b - a for a, b in zip(stamps, stamps[1:])]
        self.assertTrue(all(abs(g - 0.02) < 0.005 for g in gaps), gaps)
        self.assertLess(abs(rospy.Time.now().to_sec() - stamps[-1]), 0.5)

        # The fake unplugs 4 s after connecting: the node must say so on /ins...
        self.assertTrue(rec.wait_for(lambda: any(m.usbstatus == 0 for m in rec.get("/ins")), 10.0),
                        "usbstatus 0 never reported after the port vanished")
        lost_at = len(rec.get("/attitude"))
        first_zero = next(i for i, m in enumerate(rec.get("/ins")) if m.usbstatus == 0)
        # ...then reconnect and reconfigure (the new port streams binary only once configured).
        self.assertTrue(rec.wait_for(
            lambda: any(m.usbstatus == 1 for m in rec.get("/ins")[first_zero:]) and
            len(rec.get("/attitude")) >= lost_at + 20, 10.0),
            "no data after the port came back")
        self.check_values(rec)
        self.assertTrue(rec.wait_for(lambda: diag_values(rec)[0] is not None and
                                     int(diag_values(rec)[0].get("connections", "0")) >= 2, 5.0))
        values, _ = diag_values(rec)
        self.assertGreater(int(values["bad packets"]), 0, "injected corrupt packets not counted")
        # The /ins rate: 50 Hz met while the sensor streams, and said to fall short (or stop)
        # across the unplugs.
        self.assertTrue(rec.wait_for(lambda: any(st.level == st.OK for st in rate_statuses(rec)), 10.0),
                        "the /ins rate never reported the 50 Hz met")
        ok = [st for st in rate_statuses(rec) if st.level == st.OK][-1]
        rate = {kv.key: kv.value for kv in ok.values}
        self.assertAlmostEqual(50.0, float(rate["Target frequency (Hz)"]), places=3)
        self.assertAlmostEqual(50.0, float(rate["Actual frequency (Hz)"]), delta=5.0)
        self.assertTrue(rec.wait_for(lambda: any(st.level != st.OK for st in rate_statuses(rec)), 10.0),
                        "an unplugged sensor's /ins rate still reported met")
        self.assertGreater(int(values["bad binary CRC"]), 0)
        self.assertGreaterEqual(int(values["link losses"]), 1)


class Replay(unittest.TestCase, ValueChecks):
    def test_replays_every_packet_of_the_capture(self):
        rec = make_recorder()
        # 100 packets, 2 s of flight at double speed: about 1 s, allow for startup.
        self.assertTrue(rec.wait_for(lambda: len(rec.get("/attitude")) >= 100, 20.0),
                        "got %d of 100 packets" % len(rec.get("/attitude")))
        time.sleep(0.5)
        self.assertEqual(100, len(rec.get("/attitude")))
        self.check_values(rec)
        t = rec.times["/attitude"]
        self.assertGreater(t[-1] - t[0], 0.6, "replay was not paced by the sensor's clock")


if __name__ == "__main__":
    mode = next((a for a in sys.argv[1:] if a in ("live", "replay")), "live")
    rospy.init_node("check_vn200_node", anonymous=True)
    # Home as the HA's `arduino` node keeps it (latched): where the fake flight starts.
    from drone_ros.msg import HomePosition
    HOME_PUB = rospy.Publisher("/home", HomePosition, queue_size=1, latch=True)
    HOME_PUB.publish(HomePosition(seq=1, latitude=45.4642, longitude=9.1900, altitude=150.0))
    cls = LiveSensor if mode == "live" else Replay
    rostest.rosrun("drone_ros", "vn200_" + mode, cls, sys.argv)
