#!/usr/bin/env python3
"""Run by test_lockstep_io.py under a master of its own: the simulator's native lockstep node
(hil.lockstep_io) beside rospy publishers and subscribers, as the flight's nodes meet it. Prints
what it saw as one JSON object. A script, not a test: roscpp allows one node a process."""
import json
import sys
import time

import rosgraph
import rospy
from drone_ros.msg import DecisionStatus, HomePosition, LockstepStep, ServoCommand, hil_data, pwm
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import Temperature

from hil import lockstep_io, sim


def wait(cond, timeout_s=20.0):
    deadline = time.monotonic() + timeout_s
    while not cond():
        if time.monotonic() > deadline:
            raise SystemExit("timed out")
        time.sleep(0.02)


def main():
    rospy.init_node("hil_sim", disable_rostime=True)
    rospy.rostime._set_rostime(rospy.Time(0, 0))
    topics = {k: rospy.resolve_name(t) for k, t in (("vn", "vn200/temperature"), ("status", "decision_status"),
                                                     ("pwm", "pwm"), ("home", "home"), ("servo_op", "servo_op"),
                                                     ("to_hil", "to_hil"))}
    io = lockstep_io.LockstepIo(topics)
    out = {"name": io.name, "second_node_refused": False}
    try:
        lockstep_io.LockstepIo(topics)
    except RuntimeError:
        out["second_node_refused"] = True
    pubs = {k: rospy.Publisher(topics[k], cls, queue_size=100) for k, cls in
            (("vn", Temperature), ("status", DecisionStatus), ("pwm", pwm), ("home", HomePosition),
             ("servo_op", ServoCommand), ("to_hil", hil_data))}
    seen = {"clock": [], "lockstep": []}
    subs = [rospy.Subscriber("/clock", Clock, lambda m: seen["clock"].append(m.clock.to_nsec()))]
    subs.append(rospy.Subscriber("hil/lockstep", LockstepStep, lambda m: seen["lockstep"].append(
        [m.clock.to_nsec(), m.ins, m.attitude, m.gps_position, m.gps_velocity, m.imu_pqr_acceleration, m.pwm,
         m.decision_status, m.home, m.way])))
    wait(lambda: all(p.get_num_connections() > 0 for p in pubs.values()))
    out["before"] = {k: io.count(k) for k in lockstep_io.KEYS}
    out["wait_for_none"] = io.wait_count("status", 1, 0.2)
    out["latest_seq_before"] = io.latest_seq("servo_op")
    for _ in range(4):
        pubs["vn"].publish(Temperature(temperature=20.0))
    for _ in range(2):
        pubs["status"].publish(DecisionStatus(controller=1))
    for usb in (1, 0, 1, 0, 1):  # the arduino node's own link-down /pwm is not the HA's report
        pubs["pwm"].publish(pwm(usbstatus=usb, velocity=60.0))
    pubs["home"].publish(HomePosition())
    for seq in (41, 42):
        pubs["servo_op"].publish(ServoCommand(seq=seq, elevator_deg=-2.5, throttle=0.5, crc32=0xDEADBEEF))
    out["waypoints_before"] = io.waypoints()
    # The guidance's record every controller step: only the waypoint index's changes are kept,
    # each at the stamp of the step that made it (a restarted controller starts again at 0).
    for t_ms, index in ((10, 0), (20, 0), (30, 1), (40, 1), (50, 2), (60, 0), (70, 0)):
        m = hil_data(waypoint_index=index)
        m.header.stamp = rospy.Time(0, t_ms * 1000000)
        pubs["to_hil"].publish(m)
    out["waited"] = {k: io.wait_count(k, n, 20.0) for k, n in
                     (("vn", 4), ("status", 2), ("pwm", 3), ("home", 1), ("servo_op", 2), ("to_hil", 7))}
    time.sleep(0.3)  # anything more would have come by now
    out["after"] = {k: io.count(k) for k in lockstep_io.KEYS}
    out["latest_seq"] = io.latest_seq("servo_op")
    out["waypoints"] = io.waypoints()
    m = io.latest("servo_op", ServoCommand)
    out["latest"] = [m.seq, m.elevator_deg, m.throttle, m.crc32]
    wait(lambda: all(sub.get_num_connections() > 0 for sub in subs))
    # The preflight's wait for every node on simulated time: this node's /clock subscriber is
    # served; a node the master lists as one that has not connected (its URI answers nothing)
    # is not, until it goes.
    master = rosgraph.Master("/late_node")
    wait(lambda: sim.clock_served(sim.GraphLook(master)))
    out["clock_served"] = sim.clock_served(sim.GraphLook(master))
    master.registerSubscriber("/clock", "rosgraph_msgs/Clock", "http://127.0.0.1:9/")
    out["clock_served_with_late_node"] = sim.clock_served(sim.GraphLook(master))
    master.unregisterSubscriber("/clock", "http://127.0.0.1:9/")
    out["clock_served_after_it_went"] = sim.clock_served(sim.GraphLook(master))
    io.publish_step(1230000, (4, 4, 4, 4, 4, 3, 3, 1, 0))
    wait(lambda: seen["clock"] and seen["lockstep"])
    out["clock"], out["lockstep"] = seen["clock"], seen["lockstep"]
    io.close()
    out["after_close"] = io.count("vn")
    out["waypoints_after_close"] = io.waypoints()
    print(json.dumps(out))


if __name__ == "__main__":
    sys.exit(main())
