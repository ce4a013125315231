"""The ROS master a flight flies on, spoken to over its own XML-RPC: the one a flight starts for
itself (hil/run_flight.py) and the one a campaign worker keeps from flight to flight
(hil/campaigns/kept_master.py).

A kept master outlives the flights, so each flight on it starts from what a new master would
hold and leaves it so: reset_for_flight() before it, forget_nodes() and clear_parameters() after.
The registrations matter for nodes that were SIGKILLed (the crash fault, a flight killed whole):
theirs stay in the master, which would send `shutdown` to their old XML-RPC address when a node
of that name registers again, an address by then perhaps another live node's."""
import os
import uuid
import xmlrpc.client

CALLER = "/run_flight"
# What a master holds between flights: roscore's parameters and the rosout node.
CORE_PARAMS = ("rosversion", "rosdistro", "run_id")
CORE_NODES = ("/rosout",)


def answers(uri):
    """The master at uri is up and answers (getPid)."""
    try:
        code, _, _ = xmlrpc.client.ServerProxy(uri).getPid(CALLER)
    except (OSError, xmlrpc.client.Error):
        return False
    return code == 1


def core_parameters():
    """roscore.xml's two parameters, as its `rosversion` commands print them (with their newline),
    from rospkg's own rosversion functions in this process rather than two Python processes."""
    from rospkg import rosversion
    distro = os.environ["ROS_DISTRO"] if "ROS_DISTRO" in os.environ else rosversion.get_distro_name_from_roscore()
    return {"rosversion": "%s\n" % (rosversion.get_version_from_package_name("roslaunch") or "<unversioned>"),
            "rosdistro": "%s\n" % (distro or "Debian")}


def set_core_parameters(uri, parameters):
    """/rosversion and /rosdistro as roscore sets them, and a new /run_id (every roslaunch checks
    it and logs under it)."""
    master = xmlrpc.client.ServerProxy(uri)
    for name, value in parameters.items():
        master.setParam(CALLER, "/" + name, value)
    master.setParam(CALLER, "/run_id", str(uuid.uuid1()))


def clear_parameters(uri):
    """Every parameter but CORE_PARAMS deleted. RuntimeError when the master does not answer."""
    master = xmlrpc.client.ServerProxy(uri)
    try:
        code, msg, tree = master.getParam(CALLER, "/")
        if code != 1:
            raise RuntimeError("the ROS master at %s would not list its parameters: %s" % (uri, msg))
        for key in sorted(tree):
            if key not in CORE_PARAMS:
                master.deleteParam(CALLER, "/" + key)
    except (OSError, xmlrpc.client.Error) as e:
        raise RuntimeError("the ROS master at %s does not answer: %s" % (uri, e))


def reset_for_flight(uri):
    """A kept master made ready for the next flight: what the last one left deleted (its nodes'
    registrations, forget_nodes: a flight killed whole never removed its own; its parameters,
    clear_parameters) and a new /run_id. RuntimeError when the master does not answer."""
    if not answers(uri):
        raise RuntimeError("the ROS master at %s does not answer" % uri)
    try:
        forget_nodes(uri)
        clear_parameters(uri)
        xmlrpc.client.ServerProxy(uri).setParam(CALLER, "/run_id", str(uuid.uuid1()))
    except (OSError, xmlrpc.client.Error) as e:
        raise RuntimeError("the ROS master at %s does not answer: %s" % (uri, e))


def _system_state(master, uri):
    """(publishers, subscribers, services) as getSystemState gives them."""
    code, msg, state = master.getSystemState(CALLER)
    if code != 1:
        raise RuntimeError("the ROS master at %s would not give its state: %s" % (uri, msg))
    return state


def registered_nodes(uri):
    """Every node with a topic or service registered in the master."""
    pubs, subs, srvs = _system_state(xmlrpc.client.ServerProxy(uri), uri)
    return sorted({n for _, names in pubs + subs + srvs for n in names})


def forget_nodes(uri, keep=CORE_NODES):
    """Unregisters every topic and service of every node but keep, in their names and with the
    XML-RPC address the master holds for them; returns the nodes' names. Nodes still running
    are not stopped by this (the flight stops its own first)."""
    master = xmlrpc.client.ServerProxy(uri)
    pubs, subs, srvs = _system_state(master, uri)
    apis = {}
    for node in sorted({n for _, names in pubs + subs + srvs for n in names} - set(keep)):
        code, _, api = master.lookupNode(CALLER, node)
        if code == 1:
            apis[node] = api
    for entries, unregister in ((pubs, master.unregisterPublisher), (subs, master.unregisterSubscriber)):
        for topic, names in entries:
            for node in names:
                if node in apis:
                    unregister(node, topic, apis[node])
    for service, names in srvs:
        code, _, service_api = master.lookupService(CALLER, service)
        for node in names:
            if node in apis and code == 1:
                master.unregisterService(node, service, service_api)
    return sorted(apis)
