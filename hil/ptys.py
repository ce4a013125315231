"""Pseudo-terminals the simulator hands to nodes as their serial ports: both ends raw, the
master non-blocking, the slave's name published under a path the node opens."""
import os
import tty


def open_raw():
    """(master, slave) of a new pty, both raw (no echo, no line discipline), the master
    non-blocking."""
    master, slave = os.openpty()
    for fd in (master, slave):
        tty.setraw(fd)
    os.set_blocking(master, False)
    return master, slave


def publish(target, link):
    """link -> target, replaced atomically: a node polling for link sees the old one or the new
    one, never none."""
    tmp = link + ".tmp"
    if os.path.lexists(tmp):
        os.unlink(tmp)
    os.symlink(target, tmp)
    os.replace(tmp, link)
