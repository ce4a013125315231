"""Free loopback ports for the nodes a flight or a test starts, chosen below the kernel's
ephemeral range. A port is picked now and bound seconds later by a node (roslaunch's start-up
lies between), and the kernel hands ports of the ephemeral range to every socket that connects or
sends without binding first: ROS's own TCP connections, the MAVLink clients of the ground-station
tests (pymavlink's udpout, MAVSDK). A flight's ground station once died on "bind 127.0.0.1:34668:
Address already in use" that way. Below the range only another explicit pick can collide, and the
pick is random over some 12,000 ports."""
import random
import socket

_LOWEST = 20000


def _ephemeral_low():
    try:
        with open("/proc/sys/net/ipv4/ip_local_port_range") as f:
            return int(f.read().split()[0])
    except (OSError, ValueError, IndexError):
        return 32768


def free_port(kind=socket.SOCK_STREAM):
    """A port of 127.0.0.1 nothing holds now (kind: SOCK_STREAM or SOCK_DGRAM)."""
    top = _ephemeral_low() - 1
    pick = random.SystemRandom()
    for _ in range(200):
        port = pick.randint(_LOWEST, top) if top > _LOWEST else 0
        with socket.socket(socket.AF_INET, kind) as s:
            try:
                s.bind(("127.0.0.1", port))
            except OSError:
                continue
            return s.getsockname()[1]
    with socket.socket(socket.AF_INET, kind) as s:  # every pick taken: the kernel's choice
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]
