"""Asking a ROS node about itself through the master and the node's own XML-RPC API, always with
a deadline: a hung node accepts the connection and never answers. hp_supervisor.py finds the
controller's process this way, and so does the HiL simulator (hil/sim.py), which also asks a node
which topics it is connected on."""
import xmlrpc.client

import rosgraph


class TimeoutTransport(xmlrpc.client.Transport):
    """An XML-RPC transport whose calls give up after timeout_s."""

    def __init__(self, timeout_s=0.5):
        super().__init__()
        self.timeout_s = timeout_s

    def make_connection(self, host):
        conn = super().make_connection(host)
        conn.timeout = self.timeout_s
        return conn


def node_uri(master, name):
    """The node's XML-RPC URI, or None (not registered, or the master gone)."""
    try:
        return master.lookupNode(name)
    except (rosgraph.MasterException, OSError, xmlrpc.client.Error):
        return None


def node_api(uri, timeout_s=0.5):
    """The node's XML-RPC API at uri, its calls bounded by timeout_s."""
    return xmlrpc.client.ServerProxy(uri, transport=TimeoutTransport(timeout_s))


def ask_pid(uri, caller_id, timeout_s=0.5):
    """The node's own answer to getPid, or None (gone: connection refused; hung: no answer)."""
    try:
        code, _, pid = node_api(uri, timeout_s).getPid(caller_id)
    except (OSError, xmlrpc.client.Error):
        return None
    return pid if code == 1 else None


def node_pid(master, name, caller_id, timeout_s=0.5):
    """The PID of the node registered as name, or None."""
    uri = node_uri(master, name)
    return None if uri is None else ask_pid(uri, caller_id, timeout_s)


def bus_info(uri, caller_id, timeout_s=0.5):
    """The node's getBusInfo connections, or None when it does not answer."""
    try:
        code, _, info = node_api(uri, timeout_s).getBusInfo(caller_id)
    except (OSError, xmlrpc.client.Error):
        return None
    return info if code == 1 else None
