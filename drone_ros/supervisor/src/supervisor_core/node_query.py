"""Asking a ROS node about itself through the master and the node's own XML-RPC API, always with
a deadline: a hung node accepts the connection and never answers. The HiL simulator (hil/sim.py)
finds the controller's process this way and asks a node which topics it is connected on
(hp_supervisor's own, in C++: ../node_query.cpp)."""
import http.client
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
    """The node's XML-RPC URI, or None (not registered, the master gone, or its answer broken
    off)."""
    try:
        return master.lookupNode(name)
    except (rosgraph.MasterException, OSError, xmlrpc.client.Error, http.client.HTTPException):
        return None


def node_api(uri, timeout_s=0.5):
    """The node's XML-RPC API at uri, its calls bounded by timeout_s."""
    return xmlrpc.client.ServerProxy(uri, transport=TimeoutTransport(timeout_s))


def _call(uri, method, caller_id, timeout_s):
    """The value of the node's own answer to method(caller_id), or None (gone: connection
    refused; hung: no answer; or a failure code)."""
    try:
        code, _, value = getattr(node_api(uri, timeout_s), method)(caller_id)
    except (OSError, xmlrpc.client.Error, http.client.HTTPException):
        return None
    return value if code == 1 else None


def ask_pid(uri, caller_id, timeout_s=0.5):
    """The node's own answer to getPid, or None."""
    return _call(uri, "getPid", caller_id, timeout_s)


def node_pid(master, name, caller_id, timeout_s=0.5):
    """The PID of the node registered as name, or None."""
    uri = node_uri(master, name)
    return None if uri is None else ask_pid(uri, caller_id, timeout_s)


def bus_info(uri, caller_id, timeout_s=0.5):
    """The node's getBusInfo connections, or None when it does not answer."""
    return _call(uri, "getBusInfo", caller_id, timeout_s)
