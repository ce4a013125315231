#!/usr/bin/env python3
"""A stand-in for an Arduino sketch built on the stock rosserial_arduino ros_lib, on a pty, written
independently of both ends of our link (arduino_ha/src/link/ and the `arduino` node) so it checks
that the node speaks to what ros_lib actually sends, not only to our own device code.

Everything on the wire is built and parsed here byte by byte from the rosserial protocol (v2,
Noetic) and the message definitions; only the std_msgs types and md5sums come from the ROS
installation (genpy), so they cannot be mistyped. The behaviour follows ros_lib's NodeHandle:

- silent until the host's topic request (a frame on topic 0): then a time request (topic 10, an
  empty std_msgs/Time), a rosserial_msgs/TopicInfo per publisher on topic 0 and per subscriber
  on topic 1 (subscribers numbered from 100, publishers from 100 + MAX_SUBSCRIBERS = 125, buffer
  sizes INPUT_SIZE/OUTPUT_SIZE = 512), and "configured";
- a wrong protocol byte while not configured is answered with a time request, as ros_lib does to
  show its version;
- publishes on ids >= 100 only while configured; asks for the time every 2.5 s while configured,
  and drops "configured" if no time reply came for 11 s or the host sent ID_TX_STOP (11);
- a frame must arrive whole within 20 ms; bad length or payload checksums drop it;
- parameters (topic 6): a rosserial_msgs/RequestParam request, then spin until the reply or 1 s;
  the caller wants exactly `length` values of its type, like getParam(name, int*/float*/char**);
- logs (topic 7): rosserial_msgs/Log, levels ROSDEBUG 0, INFO 1, WARN 2, ERROR 3, FATAL 4.

The sketch it runs (Sketch below): advertise `chatter` (std_msgs/String) and `battery_v`
(std_msgs/Float32), subscribe to `led` (std_msgs/Bool) and `setpoint` (std_msgs/Int32); once
connected read three parameters, then every 100 ms publish both topics and every second log
once at each level. What it receives is recorded for the test (RoslibDevice.events).

Run alone: roslib_device.py --port /tmp/fake_due   (then point the `arduino` node at it)."""
import argparse
import os
import struct
import termios
import threading
import time
import tty

from std_msgs.msg import Bool, Float32, Int32, String

# rosserial_msgs/TopicInfo ids (reserved topics).
ID_PUBLISHER = 0
ID_SUBSCRIBER = 1
ID_PARAMETER_REQUEST = 6
ID_LOG = 7
ID_TIME = 10
ID_TX_STOP = 11
# ros_lib's NodeHandle_ defaults on a Due (ros.h: NodeHandle_<ArduinoHardware>).
MAX_SUBSCRIBERS = 25
INPUT_SIZE = 512
OUTPUT_SIZE = 512
SYNC_SECONDS = 5
SERIAL_MSG_TIMEOUT_MS = 20
PROTOCOL_VER2 = 0xFE
# rosserial_msgs/Log levels.
ROSDEBUG, INFO, WARN, ERROR, FATAL = 0, 1, 2, 3, 4


def frame(topic_id, payload):
    """A rosserial v2 frame: ff fe, length (LE) and its checksum, topic (LE), payload, checksum."""
    n = len(payload)
    len_lo, len_hi = n & 0xFF, (n >> 8) & 0xFF
    topic_lo, topic_hi = topic_id & 0xFF, (topic_id >> 8) & 0xFF
    out = bytearray([0xFF, PROTOCOL_VER2, len_lo, len_hi, 255 - ((len_lo + len_hi) % 256), topic_lo, topic_hi])
    out += payload
    out.append(255 - ((topic_lo + topic_hi + sum(payload)) % 256))
    return bytes(out)


# --- ROS serialization of the few types involved, from their .msg definitions ---
def ser_string(text):
    data = text.encode() if isinstance(text, str) else bytes(text)
    return struct.pack("<I", len(data)) + data


def ser_topic_info(topic_id, topic_name, message_type, md5sum, buffer_size):
    # uint16 topic_id, string topic_name, string message_type, string md5sum, int32 buffer_size
    return (struct.pack("<H", topic_id) + ser_string(topic_name) + ser_string(message_type) + ser_string(md5sum)
            + struct.pack("<i", buffer_size))


def ser_log(level, text):
    return struct.pack("<B", level) + ser_string(text)  # uint8 level, string msg


def ser_param_request(name):
    return ser_string(name)  # string name


def ser_time(sec, nsec):
    return struct.pack("<II", sec, nsec)  # std_msgs/Time: time data (uint32 sec, uint32 nsec)


class Reader:
    """Bounded reads from a ROS serialization; IndexError past the end."""

    def __init__(self, data):
        self.data, self.pos = bytes(data), 0

    def take(self, n):
        if self.pos + n > len(self.data):
            raise IndexError("truncated")
        chunk = self.data[self.pos:self.pos + n]
        self.pos += n
        return chunk

    def u32(self):
        return struct.unpack("<I", self.take(4))[0]

    def array(self, item):
        return [item() for _ in range(self.u32())]


def de_param_response(data):
    # int32[] ints, float32[] floats, string[] strings
    r = Reader(data)
    ints = r.array(lambda: struct.unpack("<i", r.take(4))[0])
    floats = r.array(lambda: struct.unpack("<f", r.take(4))[0])
    strings = r.array(lambda: r.take(r.u32()).decode())
    return ints, floats, strings


def de_time(data):
    sec, nsec = struct.unpack("<II", bytes(data[:8]))
    return sec, nsec


class Endpoint:
    def __init__(self, topic_name, msg_class):
        self.topic_name = topic_name
        self.msg_type = msg_class._type      # from the ROS installation, not typed here
        self.md5sum = msg_class._md5sum
        self.id = None


class RoslibDevice:
    """ros_lib's NodeHandle over a pty; `port` becomes a symlink to the pty's slave end."""

    def __init__(self, port, lose_subscriber_infos_once=False):
        """lose_subscriber_infos_once: the first answer to a topic request loses its subscribers'
        TopicInfos on the wire (never written), as a full USB buffer loses them."""
        self.port = port
        self.lose_subscriber_infos = lose_subscriber_infos_once
        self.master, self.slave = os.openpty()
        tty.setraw(self.slave)
        attrs = termios.tcgetattr(self.slave)
        attrs[3] &= ~termios.ECHO
        termios.tcsetattr(self.slave, termios.TCSANOW, attrs)
        os.set_blocking(self.master, False)
        tmp = port + ".tmp"
        if os.path.lexists(tmp):
            os.unlink(tmp)
        os.symlink(os.ttyname(self.slave), tmp)
        os.rename(tmp, port)
        self.t0 = time.monotonic()
        self.publishers, self.subscribers = [], []
        self.configured = False
        self.lock = threading.Lock()
        self.events = []         # (kind, detail) in order, for the test
        self.sent = []           # (topic_id, payload) of every frame written
        self.rx = bytearray()    # bytes read and not yet consumed by the state machine
        self.mode = "sync"
        self.frame_deadline_ms = 0
        self.remaining = self.checksum = self.topic = 0
        self.payload = bytearray()
        self.param_reply = None
        self.rt_time = 0
        self.sec_offset = self.nsec_offset = 0
        self.last_sync_time = self.last_sync_receive_time = 0

    # --- the Arduino "hardware": a millisecond clock and the serial port ---
    def millis(self):
        return int((time.monotonic() - self.t0) * 1000) & 0xFFFFFFFF

    def write(self, data):
        try:
            os.write(self.master, data)
        except (BlockingIOError, OSError):
            pass  # host not reading: lost, as on a full USB buffer

    def record(self, kind, detail):
        with self.lock:
            self.events.append((kind, detail))

    def close(self):
        if os.path.lexists(self.port):
            os.unlink(self.port)
        for fd in (self.master, self.slave):
            try:
                os.close(fd)
            except OSError:
                pass

    # --- ros::NodeHandle ---
    def advertise(self, ep):
        ep.id = 100 + MAX_SUBSCRIBERS + len(self.publishers)
        self.publishers.append(ep)

    def subscribe(self, ep, callback):
        ep.id = 100 + len(self.subscribers)
        ep.callback = callback
        self.subscribers.append(ep)

    def connected(self):
        return self.configured

    def publish(self, topic_id, payload):
        if topic_id >= 100 and not self.configured:
            return  # ros_lib drops user topics until negotiated
        if len(payload) + 8 > OUTPUT_SIZE:
            return
        with self.lock:
            self.sent.append((topic_id, bytes(payload)))
        self.write(frame(topic_id, payload))

    def request_sync_time(self):
        self.publish(ID_TIME, ser_time(0, 0))
        self.rt_time = self.millis()
        self.record("time_request", self.rt_time)

    def sync_time(self, payload):
        offset = (self.millis() - self.rt_time) & 0xFFFFFFFF
        sec, nsec = de_time(payload)
        # ros_lib adds the whole round trip (not half of it) to the host's time; so do we.
        sec += offset // 1000
        nsec += (offset % 1000) * 1000000
        ms = self.millis()
        self.sec_offset = sec - ms // 1000 - 1
        self.nsec_offset = nsec - (ms % 1000) * 1000000 + 1000000000
        self.sec_offset += self.nsec_offset // 1000000000
        self.nsec_offset %= 1000000000
        self.last_sync_receive_time = ms
        self.record("time_reply", de_time(payload))

    def now(self):
        ms = self.millis()
        nsec = (ms % 1000) * 1000000 + self.nsec_offset
        return ms // 1000 + self.sec_offset + nsec // 1000000000, nsec % 1000000000

    def negotiate_topics(self):
        for p in self.publishers:
            self.publish(ID_PUBLISHER, ser_topic_info(p.id, p.topic_name, p.msg_type, p.md5sum, OUTPUT_SIZE))
        announced = [p.id for p in self.publishers]
        if self.lose_subscriber_infos:
            self.lose_subscriber_infos = False
        else:
            for s in self.subscribers:
                self.publish(ID_SUBSCRIBER, ser_topic_info(s.id, s.topic_name, s.msg_type, s.md5sum, INPUT_SIZE))
            announced += [s.id for s in self.subscribers]
        self.configured = True
        self.record("negotiated", announced)

    def log(self, level, text):
        self.publish(ID_LOG, ser_log(level, text))

    def spin_once(self):
        c_time = self.millis()
        if (c_time - self.last_sync_receive_time) & 0xFFFFFFFF > SYNC_SECONDS * 2200 and self.configured:
            self.configured = False
            self.record("sync_lost", c_time)
        if self.mode != "sync" and c_time > self.frame_deadline_ms:
            self.mode = "sync"  # the frame stopped arriving: start over
        try:
            self.rx += os.read(self.master, 4096)
        except (BlockingIOError, OSError):
            pass
        while self.rx:
            self._step(self.rx.pop(0), c_time)
        if self.configured and (c_time - self.last_sync_time) & 0xFFFFFFFF > SYNC_SECONDS * 500:
            self.request_sync_time()
            self.last_sync_time = c_time

    def _step(self, byte, c_time):
        """ros_lib's receive state machine, one byte at a time."""
        if self.mode == "payload":
            self.payload.append(byte)
            self.checksum += byte
            self.remaining -= 1
            if self.remaining == 0:
                self.mode = "checksum"
        elif self.mode == "sync":
            if byte == 0xFF:
                self.mode = "protocol"
                self.frame_deadline_ms = c_time + SERIAL_MSG_TIMEOUT_MS
        elif self.mode == "protocol":
            if byte == PROTOCOL_VER2:
                self.mode = "len_lo"
            else:
                self.mode = "sync"
                if not self.configured:
                    self.request_sync_time()  # shows the host which protocol we speak
        elif self.mode == "len_lo":
            self.remaining, self.checksum, self.mode = byte, byte, "len_hi"
        elif self.mode == "len_hi":
            self.remaining += byte << 8
            self.checksum += byte
            self.mode = "len_checksum"
        elif self.mode == "len_checksum":
            self.checksum += byte
            self.mode = "topic_lo" if self.checksum % 256 == 255 else "sync"
        elif self.mode == "topic_lo":
            self.topic, self.checksum, self.mode = byte, byte, "topic_hi"
        elif self.mode == "topic_hi":
            self.topic += byte << 8
            self.checksum += byte
            self.payload = bytearray()
            self.mode = "payload" if self.remaining > 0 else "checksum"
            if self.remaining > INPUT_SIZE:
                self.mode = "sync"  # ros_lib would overrun message_in; we just drop it
        elif self.mode == "checksum":
            self.mode = "sync"
            if (self.checksum + byte) % 256 == 255:
                self._dispatch(self.topic, bytes(self.payload), c_time)
            else:
                self.record("bad_checksum", self.topic)

    def _dispatch(self, topic, payload, c_time):
        if topic == ID_PUBLISHER:
            self.record("topic_request", payload)
            self.request_sync_time()
            self.negotiate_topics()
            self.last_sync_time = self.last_sync_receive_time = c_time
        elif topic == ID_TIME:
            self.sync_time(payload)
        elif topic == ID_PARAMETER_REQUEST:
            self.param_reply = payload
        elif topic == ID_TX_STOP:
            self.configured = False
            self.record("tx_stop", None)
        elif 100 <= topic < 100 + len(self.subscribers):
            sub = self.subscribers[topic - 100]
            self.record("received", (sub.topic_name, payload))
            sub.callback(payload)
        else:
            self.record("unknown_topic", topic)

    def get_param(self, name, kind, length=1, timeout_ms=1000):
        """getParam(name, int*/float*/char**, length): the values, or None as ros_lib's false."""
        self.param_reply = None
        self.publish(ID_PARAMETER_REQUEST, ser_param_request(name))
        end = self.millis() + timeout_ms
        while self.param_reply is None:
            self.spin_once()
            if self.millis() > end:
                self.log(WARN, "Failed to get param: timeout expired")
                return None
            time.sleep(0.001)
        try:
            ints, floats, strings = de_param_response(self.param_reply)
        except (IndexError, UnicodeDecodeError):
            return None
        values = {"int": ints, "float": floats, "string": strings}[kind]
        if len(values) != length:
            self.log(WARN, "Failed to get param: length mismatch")
            return None
        return values


class Sketch:
    """setup() and loop() of the sketch under test, on a RoslibDevice."""

    PARAMS = (("device/rate_hz", "int"), ("device/gain", "float"), ("device/label", "string"))

    def __init__(self, device):
        self.nh = device
        self.chatter = Endpoint("chatter", String)
        self.battery = Endpoint("battery_v", Float32)
        self.led = Endpoint("led", Bool)
        self.setpoint = Endpoint("setpoint", Int32)
        self.stop = False
        self.count = 0

    def setup(self):
        self.nh.advertise(self.chatter)
        self.nh.advertise(self.battery)
        self.nh.subscribe(self.led, lambda payload: None)
        self.nh.subscribe(self.setpoint, lambda payload: None)
        while not self.nh.connected() and not self.stop:
            self.nh.spin_once()
            time.sleep(0.001)
        for name, kind in self.PARAMS:
            if self.stop:
                return
            self.nh.record("param", (name, kind, self.nh.get_param(name, kind)))

    def loop(self):
        last_publish = last_log = -10000
        while not self.stop:
            ms = self.nh.millis()
            if ms - last_publish >= 100:
                last_publish = ms
                self.count += 1
                self.nh.publish(self.chatter.id, ser_string("hello from ros_lib %d" % self.count))
                self.nh.publish(self.battery.id, struct.pack("<f", 11.5))
            if ms - last_log >= 1000:
                last_log = ms
                for level, name in ((ROSDEBUG, "debug"), (INFO, "info"), (WARN, "warn"), (ERROR, "error"),
                                    (FATAL, "fatal")):
                    self.nh.log(level, "roslib_device %s" % name)
            self.nh.spin_once()
            time.sleep(0.002)

    def run(self):
        self.setup()
        self.loop()


class RunningSketch:
    """The sketch on its own device, run in a thread of its own, as the link stories run it;
    stop() ends both."""

    def __init__(self, port, **device_options):
        self.device = RoslibDevice(port, **device_options)
        self.sketch = Sketch(self.device)
        self.thread = threading.Thread(target=self.sketch.run, daemon=True)
        self.thread.start()

    def events(self, kind):
        """The details of the device's events of this kind, in order."""
        with self.device.lock:
            return [d for k, d in self.device.events if k == kind]

    def stop(self):
        self.sketch.stop = True
        self.thread.join(timeout=5.0)
        self.device.close()


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--port", required=True, help="path of the symlink to create for the host")
    args = parser.parse_args()
    device = RoslibDevice(args.port)
    sketch = Sketch(device)
    try:
        sketch.run()
    except KeyboardInterrupt:
        pass
    finally:
        device.close()
        for kind, detail in device.events:
            print(kind, detail)


if __name__ == "__main__":
    main()
