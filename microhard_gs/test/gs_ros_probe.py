#!/usr/bin/env python3
"""ROS side of the microhard_gs tests and benchmark (a helper, not a test).

Plays the controller: publishes /data at a fixed rate with a position, and /decision_status
when told on stdin ("decision <controller> <reasons_at_switch> <altitude_agl_ft>"). Reports what
microhard_gs publishes (/way, /operator_command, its /diagnostics, and the controller's when a
test runs the real one) as JSON lines on stdout, so the
test process itself never has to be a ROS node.
"""
import argparse
import io
import json
import sys
import threading
import time
import zlib

import rospy
from diagnostic_msgs.msg import DiagnosticArray
from drone_ros.msg import DecisionStatus, HomePosition, OperatorCommand, data, way


def emit(obj):
    sys.stdout.write(json.dumps(obj) + "\n")
    sys.stdout.flush()


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--lat", type=float, required=True)
    parser.add_argument("--lon", type=float, required=True)
    parser.add_argument("--alt", type=float, required=True)
    parser.add_argument("--rate", type=float, default=20.0)
    args = parser.parse_args(rospy.myargv()[1:])

    rospy.init_node("gs_ros_probe", anonymous=True, disable_signals=True)
    data_pub = rospy.Publisher("/data", data, queue_size=10)
    decision_pub = rospy.Publisher("/decision_status", DecisionStatus, queue_size=10, latch=True)
    # Home as the HA's `arduino` node keeps it (latched); the ground station takes no other.
    home_pub = rospy.Publisher("/home", HomePosition, queue_size=1, latch=True)
    home_pub.publish(HomePosition(seq=1, latitude=args.lat, longitude=args.lon, altitude=args.alt))

    def on_way(msg):
        n = msg.fp
        emit({"topic": "way", "fp": n, "north": list(msg.north[:n]), "east": list(msg.east[:n]),
              "height": list(msg.height[:n]), "velocity": list(msg.velocity[:n])})

    def on_command(msg):
        # msg/OperatorCommand.msg's crc32, as the HA checks it: zlib crc32 over the
        # serialization of every field before it.
        raw = io.BytesIO()
        msg.serialize(raw)
        crc_ok = msg.crc32 == zlib.crc32(raw.getvalue()[:-4]) & 0xFFFFFFFF
        emit({"topic": "operator_command", "command": msg.command, "request_id": msg.request_id,
              "use_current": msg.use_current, "latitude": msg.latitude, "longitude": msg.longitude,
              "altitude": msg.altitude, "crc_ok": crc_ok})

    def on_diagnostics(msg):
        for status in msg.status:
            level = ord(status.level) if isinstance(status.level, bytes) else status.level
            values = {kv.key: kv.value for kv in status.values}
            if "microhard_gs" in status.name:
                emit({"topic": "diagnostics", "level": level, "values": values})
            elif "performance controller" in status.name:  # the real controller, when a test runs it
                emit({"topic": "controller_diagnostics", "level": level, "values": values})

    subscribers = [rospy.Subscriber("/way", way, on_way),
                   rospy.Subscriber("/operator_command", OperatorCommand, on_command),
                   rospy.Subscriber("/diagnostics", DiagnosticArray, on_diagnostics)]
    connected = False
    last_waiting_s = 0.0

    def read_stdin():
        for line in sys.stdin:
            parts = line.split()
            if len(parts) == 4 and parts[0] == "decision":
                status = DecisionStatus()
                status.stamp = rospy.Time.now()
                status.controller = int(parts[1])
                status.reasons_at_switch = int(parts[2])
                status.reasons = int(parts[2])
                status.altitude_agl_ft = float(parts[3])
                decision_pub.publish(status)
                emit({"topic": "decision_sent", "controller": status.controller})
        rospy.signal_shutdown("stdin closed")

    threading.Thread(target=read_stdin, daemon=True).start()
    emit({"topic": "ready"})
    rate = rospy.Rate(args.rate)
    msg = data()
    msg.lla.x, msg.lla.y, msg.lla.z = args.lat, args.lon, args.alt
    msg.velocity.x, msg.velocity.y = 15.0, 5.0
    msg.angle.z = 0.3
    msg.air_velocity = 55.0
    msg.voltage = 12.4
    msg.PICCIC = 1
    msg.autothrottle = 0.6
    msg.a_usbstatus = 1
    msg.v_usbstatus = 1
    while not rospy.is_shutdown():
        # Tell the test once microhard_gs's publishers reach us (earlier messages would be lost),
        # and once it is gone: /way and /operator_command are its alone (a test that restarts
        # the node waits for both).
        missing = [t.name for t in subscribers + [data_pub, decision_pub] if t.get_num_connections() == 0]
        if not connected and not missing:
            connected = True
            emit({"topic": "connected"})
        elif not connected and time.monotonic() - last_waiting_s >= 5.0:
            # For a test that gives up waiting: which of microhard_gs's ends never reached us.
            last_waiting_s = time.monotonic()
            emit({"topic": "waiting", "missing": missing})
        elif connected and all(sub.get_num_connections() == 0 for sub in subscribers[:2]):
            connected = False
            emit({"topic": "disconnected"})
        msg.header.stamp = rospy.Time.now()
        data_pub.publish(msg)
        try:
            rate.sleep()
        except rospy.ROSInterruptException:
            break


if __name__ == "__main__":
    main()
