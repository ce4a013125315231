"""A scripted flight written to a bag with the rosbag API, at the rates the real topics have:
the HP flies a circle, crashes (its commands stop), the HA takes over with REASON_NO_COMMAND,
the restarted HP is watched (RECOVERING) and gets control back after the stable window.

Used by the report tests and by the markers rostest; SCRIPT is the truth they check against."""
import math
import zlib
import io

import rosbag
import rospy
from drone_ros.msg import DecisionStatus, HilTruth, ServoCommand, data, ins, pwm, way

T0_S = 1000.0            # ROS time of the first message (the report counts from here)
DECISION_HZ = 100.0
HP_CRASH_S = 30.0        # the HP's last command
HP_BACK_S = 45.0         # the restarted HP's first command
STABLE_WINDOW_S = 2.0    # as aircraft/DG808/limits.yaml decision.stable_window_s
NO_COMMAND_TIMEOUT_S = 0.05
END_S = 60.0
HOME = (38.9717, -95.2353, 250.0)  # lat, lon [deg], alt [m]

C = DecisionStatus
# (time from the start [s], controller after, the reasons the switch carries)
SWITCHES = (
    (round(HP_CRASH_S + NO_COMMAND_TIMEOUT_S, 2), C.CONTROLLER_HA, C.REASON_NO_COMMAND),
    (HP_BACK_S, C.CONTROLLER_RECOVERING, 0),
    (HP_BACK_S + STABLE_WINDOW_S, C.CONTROLLER_HP, 0),
)
LAST_DECISION_S = END_S - 1.0 / DECISION_HZ


def controller_at(t_s):
    current = C.CONTROLLER_HP
    for switch_s, controller, _ in SWITCHES:
        if t_s >= switch_s - 1e-9:
            current = controller
    return current


def waypoints():
    return [(1200.0 * math.cos(math.radians(a)), 1200.0 * math.sin(math.radians(a)), 300.0)
            for a in range(0, 360, 45)]


def _state(t_s):
    """A plausible aircraft: a 1500 ft circle at 60 ft/s, tighter and lower while the HA flies."""
    radius_ft = 1500.0 if controller_at(t_s) == C.CONTROLLER_HP else 400.0
    angle = 60.0 * t_s / 1500.0
    north, east = radius_ft * math.cos(angle), radius_ft * math.sin(angle)
    height = 300.0 + 20.0 * math.sin(t_s / 7.0)
    heading = (math.degrees(angle) + 90.0) % 360.0
    return north, east, height, heading


def _lla(north_ft, east_ft, height_ft):
    lat0, lon0, alt0 = HOME
    r_m = 6378137.0
    lat = lat0 + math.degrees(north_ft * 0.3048 / r_m)
    lon = lon0 + math.degrees(east_ft * 0.3048 / (r_m * math.cos(math.radians(lat0))))
    return lat, lon, alt0 + height_ft * 0.3048


def _servo_command(seq, stamp, t_s):
    cmd = ServoCommand(seq=seq, stamp=stamp, throttle=0.5 + 0.1 * math.sin(t_s),
                       elevator_deg=-2.0 + math.sin(t_s / 3.0), aileron_deg=5.0 * math.sin(t_s / 5.0),
                       rudder_deg=0.5, alpha_est_deg=4.0, beta_est_deg=0.0, estimator_converged=True,
                       sensor_links_healthy=True)
    buf = io.BytesIO()
    cmd.serialize(buf)
    cmd.crc32 = zlib.crc32(buf.getvalue()[:38])
    return cmd


def hp_alive(t_s):
    return t_s <= HP_CRASH_S + 1e-9 or t_s >= HP_BACK_S - 1e-9


def write(path, with_truth=True, end_s=END_S, t0_s=T0_S, chunk_threshold=768 * 1024,
          received_after_s=0.0, with_home=False, ha_clock_steps=()):
    """Writes the flight; returns the number of messages. received_after_s puts the recorder's
    receive times on another clock than the stamps (a lockstep HiL: stamps on the simulator's
    clock from 0, receive times on the wall clock). ha_clock_steps, (from_s, by_s) pairs, moves
    the HA's stamps by by_s from from_s on, as a rosserial time sync does to the HA's clock."""
    count = 0
    steps = int(round(end_s * DECISION_HZ))
    last_seq = 0
    with rosbag.Bag(path, "w", chunk_threshold=chunk_threshold) as bag:
        def put(topic, message, t_s):
            nonlocal count
            bag.write(topic, message, rospy.Time.from_sec(t0_s + t_s + received_after_s))
            count += 1

        plan = way(north=[0.0] * 32, east=[0.0] * 32, height=[0.0] * 32, velocity=[0.0] * 32,
                   fp=len(waypoints()))
        for i, (n, e, h) in enumerate(waypoints()):
            plan.north[i], plan.east[i], plan.height[i], plan.velocity[i] = n, e, h, 60.0
        put("/way", plan, 0.0)
        if with_home:  # the HA's latched home, as rosbag records a latched topic: first
            from drone_ros.msg import HomePosition
            put("/home", HomePosition(seq=1, latitude=HOME[0], longitude=HOME[1], altitude=HOME[2]), 0.0)

        for k in range(steps):
            t_s = k / DECISION_HZ
            stamp = rospy.Time.from_sec(t0_s + t_s)
            north, east, height, heading = _state(t_s)
            controller = controller_at(t_s)
            if hp_alive(t_s):
                # the restarted controller counts afresh from 0
                last_seq = k if t_s < HP_BACK_S else k - int(round(HP_BACK_S * DECISION_HZ))
                put("/servo_op", _servo_command(last_seq, stamp, t_s), t_s)
            ha_clock_s = t_s + sum(by_s for from_s, by_s in ha_clock_steps if t_s >= from_s - 1e-9)
            status = DecisionStatus(stamp=rospy.Time.from_sec(t0_s + ha_clock_s + 0.002), controller=controller,
                                    last_seq=last_seq, airspeed_ftps=60.0, altitude_agl_ft=height,
                                    state_region_max=0.3, actuator_region_max=0.2,
                                    restart_count=0 if t_s < SWITCHES[0][0] else 1)
            if controller != C.CONTROLLER_HP:
                status.reasons_at_switch = SWITCHES[0][2]
            if not hp_alive(t_s) and t_s >= SWITCHES[0][0] - 1e-9:
                status.reasons = C.REASON_NO_COMMAND
                status.restart_requested = t_s < SWITCHES[0][0] + 0.1
            if hp_alive(t_s):
                status.stable_for_s = t_s if t_s < HP_BACK_S else t_s - HP_BACK_S
            status.throttle, status.elevator_deg, status.aileron_deg, status.rudder_deg = 0.45, -1.5, 3.0, 0.2
            put("/decision_status", status, t_s)

            if with_truth:
                truth = HilTruth(north_ft=north, east_ft=east, height_above_home_ft=height,
                                 heading_deg=heading, roll_deg=20.0 if controller else 8.0, pitch_deg=2.0,
                                 r_deg_s=2.3, accel_z_ft_s2=-32.2, airspeed_ftps=60.0, groundspeed_ftps=58.0,
                                 alpha_deg=4.0, elevator_deg=-1.5, aileron_deg=3.0, rudder_deg=0.2,
                                 throttle=0.45, ha_elevator_deg=-1.0, ha_aileron_deg=4.0,
                                 ha_rudder_deg=0.0, ha_throttle=0.4, controller=controller)
                truth.header.stamp = stamp
                truth.header.frame_id = "map"
                truth.latitude_deg, truth.longitude_deg, truth.altitude_msl_m = _lla(north, east, height)
                put("/hil/truth", truth, t_s)

            d = data()
            d.header.stamp = stamp
            d.angle.x, d.angle.y, d.angle.z = math.radians(8.0), math.radians(2.0), math.radians(heading)
            d.lla.x, d.lla.y, d.lla.z = _lla(north, east, height)
            d.acceleration.z = -1.0
            d.angrate.z = math.radians(2.3)
            d.velocity.x, d.velocity.y = 17.0, 5.0
            d.air_velocity = 60.0
            d.a_usbstatus = d.v_usbstatus = 1
            if hp_alive(t_s):
                put("/data", d, t_s)

            if k % 2 == 0:  # the HA's /pwm at 50 Hz
                p = pwm(PICCIC=1, velocity=60.0, usbstatus=1 if hp_alive(t_s) else 0)
                p.header.stamp = stamp
                put("/pwm", p, t_s)
            if k % 25 == 0:  # INS status at 4 Hz
                status_msg = ins(usbstatus=1, ins_status=2, num_sats=9, gps_fix=3)
                status_msg.header.stamp = stamp
                put("/ins", status_msg, t_s)
    return count
