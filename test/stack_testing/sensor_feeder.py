"""Publishes generated sensor topics for controller_DG808 rostests and benchmarks: the DG808 in
straight and level flight at 60 ft/s heading north over home, at 50 Hz, plus a 4-waypoint plan.
Private parameters: rate_hz (default 50), stop_after_s (0 = never)."""
import math

import rospy
from drone_ros.msg import HomePosition, ins, pwm, way
from geometry_msgs.msg import Point, Twist
from sensor_msgs.msg import BatteryState, FluidPressure, Imu, NavSatFix, NavSatStatus

FT = 0.3048
G = 9.80665


class SensorFeeder:
    """The DG808 in straight and level flight at 60 ft/s heading north over home."""

    def __init__(self):
        self.pubs = {
            "pwm": rospy.Publisher("/pwm", pwm, queue_size=10),
            "ins": rospy.Publisher("/ins", ins, queue_size=10),
            "pos": rospy.Publisher("/gps_position", NavSatFix, queue_size=10),
            "vel": rospy.Publisher("/gps_velocity", Twist, queue_size=10),
            "imu": rospy.Publisher("/imu_PQR_acceleration", Imu, queue_size=10),
            "att": rospy.Publisher("/attitude", Point, queue_size=10),
            "pressure": rospy.Publisher("/pressure", FluidPressure, queue_size=10),
            "battery": rospy.Publisher("/battery_state", BatteryState, queue_size=10),
        }
        self.way_pub = rospy.Publisher("/way", way, queue_size=1, latch=True)
        plan = way()
        for i, (n, e) in enumerate([(1000.0, 0.0), (1000.0, 2000.0), (-1000.0, 2000.0),
                                    (-1000.0, 0.0)]):
            plan.north[i], plan.east[i], plan.height[i], plan.velocity[i] = n, e, 200.0, 60.0
        plan.fp = 4
        self.way_pub.publish(plan)
        # Home as the HA's `arduino` node keeps it: latched on /home.
        self.home_pub = rospy.Publisher("/home", HomePosition, queue_size=1, latch=True)
        self.home_pub.publish(HomePosition(seq=1, latitude=40.0, longitude=-83.0, altitude=250.0))

    def publish(self, t):
        """Publishes one sample of every sensor topic for time t [s] since start."""
        vt = 60.0 * FT
        alpha = 0.0417
        north_m = vt * t
        stamp = rospy.Time.now()
        m = pwm()
        m.header.stamp = stamp
        m.PICCIC = 1
        m.Throttle, m.Elevator, m.velocity, m.usbstatus = 0.33, 0.006, 60.0, 1
        self.pubs["pwm"].publish(m)
        s = ins()
        s.header.stamp = stamp
        s.usbstatus, s.gps_fix, s.num_sats = 1, 3, 9
        self.pubs["ins"].publish(s)
        fix = NavSatFix()
        fix.header.stamp = stamp
        fix.status.status = NavSatStatus.STATUS_FIX
        fix.latitude = 40.0 + math.degrees(north_m / 6378137.0)
        fix.longitude = -83.0
        fix.altitude = 250.0 + 200.0 * FT
        self.pubs["pos"].publish(fix)
        v = Twist()
        v.linear.x = vt
        self.pubs["vel"].publish(v)
        imu = Imu()
        imu.header.stamp = stamp
        imu.linear_acceleration.x = -G * math.sin(alpha)
        imu.linear_acceleration.z = -G * math.cos(alpha)
        self.pubs["imu"].publish(imu)
        self.pubs["att"].publish(Point(0.0, alpha, 0.0))
        self.pubs["pressure"].publish(FluidPressure(fluid_pressure=98500.0))
        self.pubs["battery"].publish(BatteryState(voltage=12.4))


def main():
    rospy.init_node("sensor_feeder")
    rate_hz = rospy.get_param("~rate_hz", 50.0)
    stop_after_s = rospy.get_param("~stop_after_s", 0.0)
    feeder = SensorFeeder()
    t0 = rospy.get_time()
    rate = rospy.Rate(rate_hz)
    while not rospy.is_shutdown():
        t = rospy.get_time() - t0
        if stop_after_s > 0.0 and t > stop_after_s:
            rospy.sleep(0.1)
            continue
        feeder.publish(t)
        rate.sleep()


if __name__ == "__main__":
    main()
