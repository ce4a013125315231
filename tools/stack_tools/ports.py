"""Free loopback ports for the nodes a flight or a test starts, chosen below the kernel's
ephemeral range. A port is picked now and bound seconds later by a node (roslaunch's start-up
lies between), and the kernel hands ports of the ephemeral range to every socket that connects or
sends without binding first: ROS's own TCP connections, the MAVLink clients of the ground-station
tests (pymavlink's udpout, MAVSDK). A flight's ground station once died on "bind 127.0.0.1:34668:
Address already in use" that way. Below the range only another explicit pick can collide: two
flights of a campaign's two workers, started within the same second, once picked the same port
(bench campaign flight #67 died on the ground-station monitor's bind). So every pick is also
written in a book shared by every process on the machine, and a port picked in the last
HOLD_S seconds, bound yet or not, is not picked again."""
import contextlib
import fcntl
import json
import os
import random
import socket
import tempfile
import time

_LOWEST = 20000
HOLD_S = 120.0  # far longer than a pick waits for its node to bind it (roslaunch's start)
BOOK = os.path.join(tempfile.gettempdir(), "drone_ros_port_picks.json")


def _ephemeral_low():
    try:
        with open("/proc/sys/net/ipv4/ip_local_port_range") as f:
            return int(f.read().split()[0])
    except (OSError, ValueError, IndexError):
        return 32768


@contextlib.contextmanager
def _recent_picks():
    """{port: when picked} of the last HOLD_S seconds, held under an exclusive lock and written
    back; an unreadable book is an empty one, and one that cannot be opened is not kept."""
    try:
        f = open(BOOK, "a+")
    except OSError:
        yield {}
        return
    with f:
        fcntl.flock(f, fcntl.LOCK_EX)
        f.seek(0)
        try:
            picks = {int(p): float(t) for p, t in json.loads(f.read() or "{}").items()}
        except (ValueError, TypeError, AttributeError):
            picks = {}
        now = time.time()
        picks = {p: t for p, t in picks.items() if 0.0 <= now - t < HOLD_S}
        yield picks
        f.seek(0)
        f.truncate()
        f.write(json.dumps({str(p): t for p, t in picks.items()}))
        f.flush()


def free_port(kind=socket.SOCK_STREAM):
    """A port of 127.0.0.1 nothing holds now and no process here picked in the last HOLD_S
    seconds (kind: SOCK_STREAM or SOCK_DGRAM)."""
    top = _ephemeral_low() - 1
    pick = random.SystemRandom()
    with _recent_picks() as picks:
        for _ in range(200):
            port = pick.randint(_LOWEST, top) if top > _LOWEST else 0
            if port in picks:
                continue
            with socket.socket(socket.AF_INET, kind) as s:
                try:
                    s.bind(("127.0.0.1", port))
                except OSError:
                    continue
                port = s.getsockname()[1]
            picks[port] = time.time()
            return port
    with socket.socket(socket.AF_INET, kind) as s:  # every pick taken: the kernel's choice
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]
