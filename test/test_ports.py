"""stack_tools.ports: the ports flights and tests hand to their nodes are free when picked and lie
below the kernel's ephemeral range, where no socket that connects or sends unbound is given them
(a flight's ground station once lost its port that way), and no two processes pick the same port
while the first one's node may still be on its way to bind it."""
import multiprocessing
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


def _pick_many(n, queue):
    queue.put([ports.free_port(socket.SOCK_DGRAM) for _ in range(n)])


def test_processes_picking_at_once_never_pick_the_same_port_nobody_has_bound_yet(tmp_path, monkeypatch):
    # Nothing binds the picks: only the book keeps them apart. 4 processes x 400 picks over some
    # 12,000 ports would pick a port twice almost surely without it.
    monkeypatch.setattr(ports, "BOOK", str(tmp_path / "picks.json"))
    ctx = multiprocessing.get_context("fork")
    queue = ctx.Queue()
    procs = [ctx.Process(target=_pick_many, args=(400, queue)) for _ in range(4)]
    for p in procs:
        p.start()
    picked = [port for _ in procs for port in queue.get(timeout=120)]
    for p in procs:
        p.join()
    assert len(picked) == 1600
    assert len(set(picked)) == len(picked)


def test_a_pick_is_free_again_once_its_hold_has_passed(tmp_path, monkeypatch):
    monkeypatch.setattr(ports, "BOOK", str(tmp_path / "picks.json"))
    port = ports.free_port()
    with ports._recent_picks() as picks:
        assert port in picks
        picks[port] -= ports.HOLD_S + 1.0
    with ports._recent_picks() as picks:
        assert port not in picks


def test_a_corrupt_book_is_read_as_empty_and_written_anew(tmp_path, monkeypatch):
    book = tmp_path / "picks.json"
    book.write_text("{not json")
    monkeypatch.setattr(ports, "BOOK", str(book))
    port = ports.free_port()
    with ports._recent_picks() as picks:
        assert list(picks) == [port]
