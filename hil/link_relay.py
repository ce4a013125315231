"""A man in the middle on the HP-HA link: the `arduino` node opens a pty the simulator owns
(where the Due's USB port would be), ha_sil serves its own pty under another name, and a thread
carries the bytes across both ways. HP-to-HA rosserial frames pass through a hook that may change
them (hil/faults/link_bitflip.py flips bits in them); everything else passes unchanged.

rosserial frame: 0xFF 0xFE len_lo len_hi len_chk topic_lo topic_hi payload[len] msg_chk, with
len_chk = 255 - (len_lo + len_hi) % 256 and msg_chk = 255 - (topic_lo + topic_hi + sum(payload)) % 256
(drone_ros/arduino_link/src/rosserial_framer.cpp)."""
import os
import select
import threading
import tty

from hil.sensors import Pty


def frame_checksum(data):
    return 255 - (sum(data) % 256)


class FrameSplitter:
    """Cuts a byte stream into rosserial frames; bytes between frames are passed on as they are."""

    def __init__(self):
        self.buf = bytearray()

    def feed(self, data):
        """Returns a list of (is_frame, bytes)."""
        self.buf += data
        out = []
        while self.buf:
            i = self.buf.find(b"\xff\xfe")
            if i < 0:
                keep = 1 if self.buf[-1:] == b"\xff" else 0
                if len(self.buf) > keep:
                    out.append((False, bytes(self.buf[:len(self.buf) - keep])))
                    del self.buf[:len(self.buf) - keep]
                break
            if i > 0:
                out.append((False, bytes(self.buf[:i])))
                del self.buf[:i]
            if len(self.buf) < 5:
                break
            n = self.buf[2] | (self.buf[3] << 8)
            if (self.buf[2] + self.buf[3] + self.buf[4]) % 256 != 255 or n > 4096:
                out.append((False, bytes(self.buf[:2])))  # not a frame start: the receiver sorts it out
                del self.buf[:2]
                continue
            total = 8 + n
            if len(self.buf) < total:
                break
            out.append((True, bytes(self.buf[:total])))
            del self.buf[:total]
        return out


def frame_topic_payload(frame):
    return frame[5] | (frame[6] << 8), frame[7:-1]


def make_frame(topic, payload):
    head = bytes([topic & 0xFF, topic >> 8])
    n = len(payload)
    return bytes([0xFF, 0xFE, n & 0xFF, n >> 8, frame_checksum([n & 0xFF, n >> 8])]) + head + payload + \
        bytes([frame_checksum(head + payload)])


class LinkRelay:
    def __init__(self, host_link, sil_link):
        self.host = Pty(host_link)  # what the arduino node opens
        self.sil_link = sil_link
        self.sil_fd = None
        self.hook = None            # hook(frame bytes) -> frame bytes, HP to HA
        self.splitter = FrameSplitter()
        self.stop = threading.Event()
        self.thread = None
        self.bytes_up = self.bytes_down = 0

    def connect(self):
        """Opens ha_sil's pty (once it exists) and starts carrying bytes."""
        if not os.path.exists(self.sil_link):
            return False
        self.sil_fd = os.open(os.path.realpath(self.sil_link), os.O_RDWR | os.O_NOCTTY | os.O_NONBLOCK)
        tty.setraw(self.sil_fd)
        self.thread = threading.Thread(target=self.run, name="link_relay", daemon=True)
        self.thread.start()
        return True

    @staticmethod
    def write_all(fd, data):
        view = memoryview(data)
        while view:
            try:
                n = os.write(fd, view)
            except BlockingIOError:
                select.select([], [fd], [], 0.05)
                continue
            view = view[n:]

    def run(self):
        host = self.host.master
        while not self.stop.is_set():
            r, _, _ = select.select([host, self.sil_fd], [], [], 0.1)
            if host in r:
                data = self.host.read()
                if data:
                    self.bytes_up += len(data)
                    out = bytearray()
                    for is_frame, chunk in self.splitter.feed(data):
                        out += self.hook(chunk) if is_frame and self.hook is not None else chunk
                    if out:
                        self.write_all(self.sil_fd, bytes(out))
            if self.sil_fd in r:
                try:
                    data = os.read(self.sil_fd, 4096)
                except (BlockingIOError, OSError):
                    data = b""
                if data:
                    self.bytes_down += len(data)
                    self.write_all(host, data)

    def close(self):
        self.stop.set()
        if self.thread is not None:
            self.thread.join(2.0)
        if self.sil_fd is not None:
            os.close(self.sil_fd)
        self.host.close()
