"""A wire tap between the `arduino` node and the SIL HA: the node opens a pty this tap owns,
the tap opens the SIL's pty, and bytes flow both ways through it. Tests use it to unplug and
replug the cable (the node's pty disappears and comes back under the same path) and to inject
garbage, corrupt and split frames in either direction. When the SIL pulls its own cable
(SIGUSR1), the tap passes that on to the node and reattaches when the SIL plugs in again."""
import os
import select
import termios
import threading
import time
import tty


def raw(fd):
    tty.setraw(fd)
    attrs = termios.tcgetattr(fd)
    attrs[3] &= ~termios.ECHO
    termios.tcsetattr(fd, termios.TCSANOW, attrs)


def frame(topic, payload):
    """rosserial v2 frame, from the protocol description."""
    n = len(payload)
    head = bytes([0xFF, 0xFE, n & 0xFF, n >> 8, 255 - (((n & 0xFF) + (n >> 8)) % 256)])
    body = bytes([topic & 0xFF, topic >> 8]) + bytes(payload)
    return head + body + bytes([255 - (sum(body) % 256)])


def ros_string(text):
    """A ROS string on the wire: uint32 length (little endian), then the bytes."""
    data = text.encode() if isinstance(text, str) else bytes(text)
    return len(data).to_bytes(4, "little") + data


def topic_info(topic_id, name, msg_type, md5, buffer_size=256):
    """rosserial_msgs/TopicInfo's serialization: uint16 topic_id, string topic_name, string
    message_type, string md5sum, int32 buffer_size."""
    return (topic_id.to_bytes(2, "little") + ros_string(name) + ros_string(msg_type) + ros_string(md5)
            + buffer_size.to_bytes(4, "little", signed=True))


def split_frames(buf):
    """Cuts whole frames off the front of buf (a well-formed stream from the node or the SIL), so
    injected bytes land between frames, never inside one. Returns the frames; buf keeps the rest."""
    out = []
    while True:
        start = buf.find(b"\xff\xfe")
        if start < 0:
            return out
        del buf[:start]
        if len(buf) < 8:
            return out
        total = (buf[2] | buf[3] << 8) + 8
        if len(buf) < total:
            return out
        out.append(bytes(buf[:total]))
        del buf[:total]


class WireTap:
    def __init__(self, device_path, node_path):
        self.device_path = device_path
        self.node_path = node_path
        self.lock = threading.Lock()
        self.to_node = []    # (bytes, split): split ones go out a few bytes per write
        self.to_device = []
        self.from_device = bytearray()
        self.from_node = bytearray()
        self.device_fd = None
        self.master = None
        self.slave = None
        self.stop = False
        self.thread = threading.Thread(target=self._run, daemon=True)

    def start(self):
        deadline = time.time() + 10.0
        while not os.path.exists(self.device_path):
            if time.time() > deadline:
                raise RuntimeError("SIL pty never appeared")
            time.sleep(0.05)
        self.device_fd = os.open(self.device_path, os.O_RDWR | os.O_NOCTTY | os.O_NONBLOCK)
        raw(self.device_fd)
        self.plug()
        self.thread.start()

    def plug(self):
        master, slave = os.openpty()
        raw(slave)
        os.set_blocking(master, False)
        tmp = self.node_path + ".tmp"
        if os.path.lexists(tmp):
            os.unlink(tmp)
        os.symlink(os.ttyname(slave), tmp)
        os.rename(tmp, self.node_path)
        with self.lock:
            self.master, self.slave = master, slave
            self.from_node.clear()

    def unplug(self):
        with self.lock:
            master, slave = self.master, self.slave
            self.master = self.slave = None
            self.to_node.clear()
        if os.path.lexists(self.node_path):
            os.unlink(self.node_path)
        for fd in (master, slave):
            if fd is not None:
                os.close(fd)

    def inject_to_node(self, data, split=False):
        with self.lock:
            self.to_node.append((bytes(data), split))

    def inject_to_device(self, data):
        with self.lock:
            self.to_device.append((bytes(data), False))

    def close(self):
        self.stop = True
        self.thread.join(timeout=2.0)
        self.unplug()
        if self.device_fd is not None:
            os.close(self.device_fd)
            self.device_fd = None

    @staticmethod
    def _drain(fd, queue):
        """Writes queued items in order; a split item a few bytes per call (every 2 ms), so the
        reader gets it in pieces yet well within its 50 ms frame timeout."""
        while queue:
            data, split = queue[0]
            n = 3 if split else len(data)
            try:
                written = os.write(fd, data[:n])
            except BlockingIOError:
                return
            except OSError:
                queue.clear()
                return
            rest = data[written:]
            if rest:
                queue[0] = (rest, split)
            else:
                queue.pop(0)
            if split:
                return  # one piece per pass: the reader sees the frame in pieces

    def _device_gone(self):
        """The SIL pulled its cable: the node's side goes too, until the SIL plugs in again."""
        os.close(self.device_fd)
        self.device_fd = None
        self.from_device.clear()
        self.to_device.clear()

    def _reattach(self):
        try:
            fd = os.open(self.device_path, os.O_RDWR | os.O_NOCTTY | os.O_NONBLOCK)
        except OSError:
            return False
        raw(fd)
        self.device_fd = fd
        return True

    def _run(self):
        while not self.stop:
            if self.device_fd is None:
                if not self._reattach():
                    time.sleep(0.01)
                    continue
                self.plug()
            with self.lock:
                master = self.master
            fds = [self.device_fd] + ([master] if master is not None else [])
            ready, _, _ = select.select(fds, [], [], 0.002)
            gone = False
            with self.lock:
                if self.device_fd in ready:
                    try:
                        data = os.read(self.device_fd, 4096)
                    except OSError:
                        data = b""
                    if not data:
                        gone = True
                    self.from_device += data
                    frames = split_frames(self.from_device)
                    if self.master is not None:  # while unplugged, the device's bytes are lost
                        self.to_node.extend((f, False) for f in frames)
                if not gone and self.master is not None and self.master in ready:
                    try:
                        self.from_node += os.read(self.master, 4096)
                    except OSError:
                        pass  # the node closed its end; it reopens on its own
                    self.to_device.extend((f, False) for f in split_frames(self.from_node))
                if not gone and self.master is not None:
                    self._drain(self.master, self.to_node)
                if not gone:
                    self._drain(self.device_fd, self.to_device)
            if gone:
                self._device_gone()
                self.unplug()
