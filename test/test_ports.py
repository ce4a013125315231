"""stack_tools.ports: the ports flights and tests hand to their nodes are free when picked and lie
below the kernel's ephemeral range, where no socket that connects or sends unbound is given them
(a flight's ground station once lost its port that way)."""
import socket

from stack_tools import ports


def test_a_picked_port_is_free_and_below_the_ephemeral_range():
    low = ports._ephemeral_low()
    for kind in (socket.SOCK_STREAM, socket.SOCK_DGRAM):
        for _ in range(50):
            port = ports.free_port(kind)
            assert 20000 <= port < low
            with socket.socket(socket.AF_INET, kind) as s:
                s.bind(("127.0.0.1", port))


def test_a_port_in_use_is_never_picked():
    held = []
    try:
        for _ in range(300):
            s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
            s.bind(("127.0.0.1", ports.free_port(socket.SOCK_DGRAM)))
            held.append(s)
        assert len({s.getsockname()[1] for s in held}) == len(held)
    finally:
        for s in held:
            s.close()
