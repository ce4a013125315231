#!/usr/bin/env python3
"""make bench-link: the HA-HP link over pseudo-terminals, SIL HA and the real `arduino` node.

Prints `metric: value unit` lines, then `machine: ...`:
  - latency from publishing /servo_op to the HA core receiving the command (p50, p99);
  - commands per second sustained when the publisher floods;
  - sensor frames per second delivered from the HA at 100 Hz;
  - bytes per 100 Hz period each way and the share of each baud budget.
Usage: bench_link.py WORKSPACE   (the catkin workspace with drone_ros built)"""
import io
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time

import rospy
from std_msgs.msg import Time

from drone_ros.msg import DecisionStatus, ServoCommand, pwm

from stack_tools.bench_machine import machine  # noqa: E402

RATE_HZ = 100
STEADY_S = 6.0
FLOOD_S = 3.0
FRAME_OVERHEAD = 8
TIME_SYNC_PER_S = 2  # the device asks for the time every 0.5 s; each ask is answered


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def wire_size(msg):
    buf = io.BytesIO()
    msg.serialize(buf)
    return len(buf.getvalue()) + FRAME_OVERHEAD


def percentile(values, p):
    values = sorted(values)
    k = min(len(values) - 1, max(0, int(round(p / 100.0 * (len(values) - 1)))))
    return values[k]


def publish_commands(pub, last_seq, duration_s, rate=None):
    """Stamped servo commands numbered on from last_seq for duration_s, one per period of rate, or
    back to back without one; returns the last seq sent."""
    seq = last_seq
    t0 = time.time()
    while time.time() - t0 < duration_s:
        seq += 1
        cmd = ServoCommand(seq=seq)
        cmd.stamp = rospy.Time.now()
        pub.publish(cmd)
        if rate is not None:
            rate.sleep()
    return seq


def print_figures(steady, flood, steady_sensors, header):
    """The metric lines: latency at 100 Hz, what the link sustains, bytes per period against
    the two baud rates' budgets, then the machine."""
    latencies_ms = [v / 1000.0 for v in steady]
    up = wire_size(pwm()) + wire_size(DecisionStatus())
    down = wire_size(ServoCommand())
    sync = wire_size(Time()) * TIME_SYNC_PER_S / RATE_HZ  # per period, each way
    up_period = up + sync
    down_period = down + sync
    print("link_latency_p50: %.3f ms" % percentile(latencies_ms, 50))
    print("link_latency_p99: %.3f ms" % percentile(latencies_ms, 99))
    print("link_latency_max: %.3f ms" % max(latencies_ms))
    print("commands_received_at_100hz: %d of %d" % (len(steady), int(STEADY_S * RATE_HZ)))
    print("commands_per_s_sustained: %.0f frames/s" % (len(flood) / FLOOD_S))
    print("sensor_frames_per_s_at_100hz: %.1f frames/s" % (2 * steady_sensors / STEADY_S))
    print("bytes_per_period_ha_to_hp: %.1f bytes" % up_period)
    print("bytes_per_period_hp_to_ha: %.1f bytes" % down_period)
    for baud in (115200, 250000):
        budget = baud / 10.0 / RATE_HZ  # 8N1: 10 bits a byte
        print("budget_%d_baud_ha_to_hp: %.0f %%" % (baud, 100.0 * up_period / budget))
        print("budget_%d_baud_hp_to_ha: %.0f %%" % (baud, 100.0 * down_period / budget))
    print("machine: %s" % header)


def main():
    header = machine("ptys (no baud limit)")
    ws = sys.argv[1]
    lib = os.path.join(ws, "devel", "lib", "drone_ros")
    tmp = tempfile.mkdtemp(prefix="bench_link_")
    port = os.path.join(tmp, "due")
    lat_log = os.path.join(tmp, "latency.txt")
    env = dict(os.environ, ROS_MASTER_URI="http://127.0.0.1:%d" % free_port(), ROS_HOME=tmp, ROS_LOG_DIR=tmp)
    os.environ.update(env)
    master_port = int(env["ROS_MASTER_URI"].rsplit(":", 1)[1])
    procs = []
    try:
        procs.append(subprocess.Popen(["rosmaster", "--core", "-p", str(master_port)], env=env,
                                      stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        time.sleep(1.5)
        procs.append(subprocess.Popen([os.path.join(lib, "ha_sil"), "--port", port, "--rate-hz", str(RATE_HZ),
                                       "--latency-log", lat_log], env=env, stderr=subprocess.DEVNULL))
        procs.append(subprocess.Popen([os.path.join(lib, "arduino"), "_port:=" + port, "_baud:=250000"], env=env,
                                      stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        rospy.init_node("bench_link", disable_signals=True)
        sensors = []
        rospy.Subscriber("pwm", pwm, lambda m: sensors.append(m.usbstatus), queue_size=1000)
        pub = rospy.Publisher("servo_op", ServoCommand, queue_size=1000, tcp_nodelay=True)
        deadline = time.time() + 20
        while (pub.get_num_connections() == 0 or not sensors or sensors[-1] != 1) and time.time() < deadline:
            time.sleep(0.05)
        if pub.get_num_connections() == 0:
            raise SystemExit("bench-link: the link never came up")
        # Steady 100 Hz: the latency a control period sees.
        sensors.clear()
        seq = publish_commands(pub, 0, STEADY_S, rospy.Rate(RATE_HZ))
        steady_sensors = sum(1 for s in sensors if s == 1)
        time.sleep(0.3)
        with open(lat_log) as fh:
            steady = [float(line.split()[1]) for line in fh if line.strip()]
        # Flood: as fast as the publisher can go, what the link sustains.
        first_flood_seq = seq + 1
        publish_commands(pub, seq, FLOOD_S)
        time.sleep(0.5)
        with open(lat_log) as fh:
            flood = [line for line in fh if line.strip() and int(line.split()[0]) >= first_flood_seq]
    finally:
        for p in reversed(procs):
            p.send_signal(signal.SIGINT)
        for p in reversed(procs):
            try:
                p.wait(timeout=5)
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait()
        shutil.rmtree(tmp, ignore_errors=True)

    print_figures(steady, flood, steady_sensors, header)


if __name__ == "__main__":
    main()
