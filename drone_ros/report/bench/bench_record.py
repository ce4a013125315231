"""Size per hour of a flight log (launch/record.launch's topics): 60 s of every recorded topic
at its real rate written with the rosbag API in rosbag record's format (768 KB chunks), then
extrapolated to an hour. Every numeric field holds a random value, as sensor noise makes real
values, so compression is not flattered by zeros. Prints `metric: value unit` lines, then the
machine.

Rates: the HA's /decision_status and /pwm at its 100 Hz (limits.yaml decision.rate_hz), /ins at
the VN-200's 100 Hz (vn200.launch rate_hz), the controller's /servo_op, /data, /to_hil at its
control rate (100 Hz, controller_param.yaml dt 0.01; or 20 Hz with an HA at 20 Hz), /hil/truth once per HA period in
HiL, /diagnostics and /rosout_agg at 1 Hz."""
import io
import os
import random
import sys
import tempfile

import genpy
import rosbag
import rospy
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus, KeyValue
from rosgraph_msgs.msg import Log

from drone_ros.msg import DecisionStatus, HilTruth, ServoCommand, data, hil_data, ins, pwm

from stack_tools.bench_machine import machine  # noqa: E402

SECONDS = 60.0
CHUNK_BYTES = 768 * 1024  # rosbag record's default --chunksize
rng = random.Random(808)


def randomized(message):
    """Every numeric field (nested, arrays) set to a random value of its type."""
    for slot, kind in zip(message.__slots__, message._slot_types):
        value = getattr(message, slot)
        if isinstance(value, genpy.Message):
            randomized(value)
        elif isinstance(value, (genpy.Time, genpy.Duration)):
            continue
        else:
            base, is_array = kind.split("[")[0], "[" in kind
            if base.startswith("float"):
                setattr(message, slot, [rng.gauss(0.0, 50.0) for _ in value] if is_array
                        else rng.gauss(0.0, 50.0))
            elif is_array:
                continue
            elif base in ("uint8", "bool"):
                setattr(message, slot, rng.randint(0, 1))
            elif base.startswith(("uint", "int")):
                setattr(message, slot, rng.randint(0, 30000))
    return message


def diagnostics():
    array = DiagnosticArray()
    for name in ("vn200: link", "arduino: link", "microhard_gs: link", "controller_DG808: timing"):
        array.status.append(DiagnosticStatus(level=0, name=name, message="OK", hardware_id="hp",
                                             values=[KeyValue("rate_hz", "100.0"), KeyValue("dropped", "0")]))
    return array


def topics(control_hz, hil):
    """(topic, rate [Hz], message factory)"""
    out = [("/decision_status", 100.0, lambda: randomized(DecisionStatus())),
           ("/pwm", 100.0, lambda: randomized(pwm())),
           ("/ins", 100.0, lambda: randomized(ins())),
           ("/servo_op", control_hz, lambda: randomized(ServoCommand())),
           ("/data", control_hz, lambda: randomized(data())),
           ("/to_hil", control_hz, lambda: randomized(hil_data())),
           ("/diagnostics", 1.0, diagnostics),
           ("/rosout_agg", 1.0, lambda: Log(level=Log.INFO, name="/controller_DG808",
                                            msg="waypoint 12 reached, next 13", file="controller_node.cpp",
                                            function="step", line=212, topics=["/servo_op", "/data"]))]
    if hil:
        out.append(("/hil/truth", 100.0, lambda: randomized(HilTruth())))
    return out


def measure(control_hz, hil, compression):
    per_topic = {}
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "flight.bag")
        with rosbag.Bag(path, "w", compression=compression, chunk_threshold=CHUNK_BYTES) as bag:
            events = []
            for topic, rate, make in topics(control_hz, hil):
                events += [(k / rate, topic, make) for k in range(int(SECONDS * rate))]
            events.sort(key=lambda e: e[0])
            for t_s, topic, make in events:
                message = make()
                bag.write(topic, message, rospy.Time.from_sec(1000.0 + t_s))
                per_topic[topic] = per_topic.get(topic, 0) + len(_serialized(message))
        size = os.path.getsize(path)
    return size * 3600.0 / SECONDS, {t: b * 3600.0 / SECONDS for t, b in per_topic.items()}


def _serialized(message):
    buf = io.BytesIO()
    message.serialize(buf)
    return buf.getvalue()


def main():
    header = machine()
    mb = 1e6
    for label, control_hz, hil in (("flight_20hz", 20.0, False), ("flight_100hz", 100.0, False),
                                   ("hil_100hz", 100.0, True)):
        for compression in ("none", "lz4"):
            per_hour, per_topic = measure(control_hz, hil, compression)
            print("record_size_%s_%s: %.0f MB/h" % (label, compression, per_hour / mb))
            if compression == "none":
                for topic, size in sorted(per_topic.items(), key=lambda kv: -kv[1]):
                    print("record_payload_%s_%s: %.1f MB/h" % (label, topic.strip("/").replace("/", "_"),
                                                               size / mb))
            sys.stdout.flush()
    print("machine: %s" % header)
    return 0


if __name__ == "__main__":
    sys.exit(main())
