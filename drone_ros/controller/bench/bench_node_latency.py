#!/usr/bin/env python3
"""controller_DG808 end-to-end latency: from the publish of the latest sensor sample to the
arrival of the next /servo_op, at 20 Hz and 100 Hz. Sensors are fed at 100 Hz (the HA's rate)
from this process; each rate gets its own roslaunch of the flight launch file (ground station on
UDP loopback, no radio needed) and its own ROS master on a free loopback port.
Two figures per rate:
- sensor-to-command: includes the wait for the controller's next timer tick (it steps on its own
  clock, not on message arrival), so it is bounded by one feed period plus processing and transport;
- step-to-receipt: from the stamp the controller puts on the command (taken as its step starts
  publishing) to its arrival here: the node's own processing and ROS transport alone.
Prints `name: value unit` lines."""
import os
import socket
import subprocess
import sys
import time

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", "..", ".."))

FEED_HZ = 100.0
MEASURE_S = 8.0


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def measure(dt_s):
    """One rate in a child process of its own (rospy initializes once per process)."""
    port = free_port()
    env = dict(os.environ, ROS_MASTER_URI="http://127.0.0.1:%d" % port, ROS_IP="127.0.0.1",
               ROS_HOSTNAME="127.0.0.1")
    log = open(os.path.join("/tmp", "bench_controller_roslaunch_%d.log" % port), "w")
    launch = subprocess.Popen(
        ["roslaunch", "-p", str(port), os.path.join(ROOT, "launch", "DG808_flight.launch"),
         "dt:=%g" % dt_s, "gs_transport:=udp", "gs_udp_remote_address:=127.0.0.1", "record:=false"], env=env, stdout=log, stderr=subprocess.STDOUT)
    try:
        out = subprocess.run([sys.executable, os.path.abspath(__file__), "--client", str(dt_s)],
                             env=env, stdout=subprocess.PIPE, check=True, timeout=90)
        pairs = [line.split() for line in out.stdout.decode().splitlines() if line.strip()]
        return (sorted(float(a) for a, _ in pairs), sorted(float(b) for _, b in pairs))
    finally:
        log.close()
        launch.terminate()
        try:
            launch.wait(timeout=15)
        except subprocess.TimeoutExpired:
            launch.kill()
            launch.wait()


def run_client(dt_s):
    # Imported here: rospy reads ROS_MASTER_URI when the node starts.
    import rospy
    from drone_ros.msg import ServoCommand
    from stack_testing.sensor_feeder import SensorFeeder

    deadline = time.monotonic() + 30.0
    while True:
        try:
            rospy.get_master().getPid()
            break
        except Exception:  # master not up yet
            if time.monotonic() > deadline:
                raise RuntimeError("no ROS master")
            time.sleep(0.2)
    rospy.init_node("bench_controller_latency", anonymous=True, disable_signals=True)
    state = {"last_pub": None, "lat": [], "transport": [], "recording": False}

    def on_cmd(msg):
        now = time.monotonic()
        if state["recording"] and state["last_pub"] is not None:
            state["lat"].append(now - state["last_pub"])
            state["transport"].append((rospy.Time.now() - msg.stamp).to_sec())

    sub = rospy.Subscriber("/servo_op", ServoCommand, on_cmd, queue_size=100, tcp_nodelay=True)
    feeder = SensorFeeder()
    t0 = time.monotonic()
    period = 1.0 / FEED_HZ
    next_t = t0
    while time.monotonic() - t0 < MEASURE_S + 3.0:
        t = time.monotonic() - t0
        feeder.publish(t)
        state["last_pub"] = time.monotonic()
        state["recording"] = t > 3.0  # node up, subscriptions connected
        next_t += period
        time.sleep(max(0.0, next_t - time.monotonic()))
    sub.unregister()
    for p in feeder.pubs.values():
        p.unregister()
    feeder.way_pub.unregister()
    feeder.home_pub.unregister()
    if not state["lat"]:
        raise RuntimeError("no /servo_op received at dt=%g" % dt_s)
    rospy.signal_shutdown("done")
    return state["lat"], state["transport"]


def pct(sorted_values, q):
    return sorted_values[min(len(sorted_values) - 1, int(q * len(sorted_values)))]


def main():
    if len(sys.argv) == 3 and sys.argv[1] == "--client":
        lat, transport = run_client(float(sys.argv[2]))
        print("\n".join("%.9f %.9f" % pair for pair in zip(lat, transport)))
        return
    results = {}
    for hz in (20, 100):
        results[hz] = measure(1.0 / hz)
    for hz, (lat, transport) in results.items():
        print("node_sensor_to_command_%dhz_p50: %.2f ms" % (hz, 1000.0 * pct(lat, 0.50)))
        print("node_sensor_to_command_%dhz_p99: %.2f ms" % (hz, 1000.0 * pct(lat, 0.99)))
        print("node_step_to_receipt_%dhz_p50: %.3f ms" % (hz, 1000.0 * pct(transport, 0.50)))
        print("node_step_to_receipt_%dhz_p99: %.3f ms" % (hz, 1000.0 * pct(transport, 0.99)))
        print("node_servo_op_%dhz_count: %d messages" % (hz, len(lat)))


if __name__ == "__main__":
    main()
