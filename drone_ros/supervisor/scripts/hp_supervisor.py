#!/usr/bin/env python3
"""hp_supervisor: the HP side's end of the HA's reset line, in software.

When the HA asks for an HP restart (a rising edge of DecisionStatus.restart_requested on
/decision_status), this node ends the controller process and starts a new one. A respawning
launch node alone is not enough: a hung controller never exits, so nothing would respawn it. The
process is found through the ROS master (lookupNode, then the node's own getPid), asked to stop
with SIGTERM, killed with SIGKILL after ~kill_grace_s, and started again after ~boot_delay_s of ROS
time (0 in flight; a HiL flight sets how long a reboot of the HP takes in simulated time). The
new process gets the same node name, so it finds the private parameters the launch file loaded;
it is this node's child and is stopped with it.

Parameters: ~node (the node to supervise, default /controller_DG808), ~package and ~type (its
executable, default drone_ros controller_DG808), ~kill_grace_s (1.0), ~boot_delay_s (0.0).

Diagnostics (/diagnostics, once a wall-clock second, "hp_supervisor: <node>"): OK while supervising, WARN
while a restart is under way, ERROR when the last one could not start the node (no executable);
its values: restarts, how the last old process ended, the PID
of the new one.
"""
import io
import os
import signal
import socket
import subprocess
import threading
import time
from urllib.parse import urlparse

import rosgraph
import roslib.packages
import rospy
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus, KeyValue
from drone_ros.msg import DecisionStatus
from stack_common.rospy_shutdown import exit_promptly

# node_query.py lies beside this file (the devel space runs it from the source folder).
from supervisor_core.node_query import ThreadMasters, ask_pid, node_uri  # noqa: E402


def restart_requested_offset():
    """The byte of restart_requested in a serialized DecisionStatus (all its fields have fixed
    sizes), found by serializing one each way: every report is read at that byte instead of
    decoded whole, a hundred times a simulated second."""
    off, on = io.BytesIO(), io.BytesIO()
    DecisionStatus(restart_requested=False).serialize(off)
    DecisionStatus(restart_requested=True).serialize(on)
    differ = [i for i, (a, b) in enumerate(zip(off.getvalue(), on.getvalue())) if a != b]
    if len(differ) != 1 or len(off.getvalue()) != len(on.getvalue()):
        raise RuntimeError("DecisionStatus.restart_requested is not one byte at a fixed place")
    return differ[0], len(off.getvalue())


RESTART_REQUESTED_AT, STATUS_BYTES = restart_requested_offset()


def local(uri):
    host = urlparse(uri).hostname
    return host in ("localhost", "127.0.0.1", socket.gethostname(), rosgraph.network.get_host_name())


def alive(pid):
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    # A dead child of roslaunch is a zombie until roslaunch reaps it.
    try:
        with open("/proc/%d/stat" % pid) as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


class Supervisor:
    def __init__(self):
        self.node = rospy.resolve_name(rospy.get_param("~node", "controller_DG808"))
        self.package = rospy.get_param("~package", "drone_ros")
        self.type = rospy.get_param("~type", "controller_DG808")
        self.kill_grace_s = float(rospy.get_param("~kill_grace_s", 1.0))
        self.boot_delay_s = float(rospy.get_param("~boot_delay_s", 0.0))
        self.masters = ThreadMasters(rospy.get_name())  # the learner's and each restart's own
        self.children = []
        self.requested = False
        self.busy = threading.Lock()
        self.restarts = 0
        self.known = (None, None)  # (uri, pid) of the node while it answered
        self.last_stop = None  # how the last restart ended the old process
        self.failure = None  # why the last restart could not start the node, if it could not
        self.started_pid = None
        self.bad_reports = 0  # /decision_status messages not of DecisionStatus's size
        self.diag_pub = rospy.Publisher("/diagnostics", DiagnosticArray, queue_size=1)
        # On the wall clock: a rospy.Timer on simulated time woke at every /clock, 1,400 times a
        # wall second in a lockstep flight, for a status a second.
        threading.Thread(target=self.diagnostics_loop, daemon=True).start()
        self.learner = threading.Thread(target=self.learn_pids, daemon=True)
        self.learner.start()
        rospy.Subscriber("decision_status", rospy.AnyMsg, self.on_report, queue_size=10)
        rospy.loginfo("hp_supervisor: restarts %s when the HA asks (boot delay %.1f s)",
                      self.node, self.boot_delay_s)

    def on_report(self, raw):
        """A /decision_status as bytes: only its restart_requested is read."""
        if len(raw._buff) != STATUS_BYTES:
            self.bad_reports += 1
            if self.bad_reports == 1:
                rospy.logwarn("hp_supervisor: a /decision_status of %d bytes, not %d: ignored (and counted "
                              "in /diagnostics as 'bad reports')", len(raw._buff), STATUS_BYTES)
            return
        self.on_request(bool(raw._buff[RESTART_REQUESTED_AT]))

    def on_request(self, requested):
        rising = requested and not self.requested
        self.requested = requested
        if not rising:
            return
        if not self.busy.acquire(blocking=False):
            rospy.logwarn("hp_supervisor: restart requested while one is under way; ignored")
            return
        threading.Thread(target=self.restart, daemon=True).start()

    def diagnostics_loop(self):
        while not rospy.is_shutdown():
            time.sleep(1.0)
            if not rospy.is_shutdown():
                self.publish_diagnostics()

    def publish_diagnostics(self):
        st = DiagnosticStatus(name="hp_supervisor: %s" % self.node, hardware_id="HP computer")
        if self.failure:
            st.level, st.message = DiagnosticStatus.ERROR, "cannot restart: %s" % self.failure
        elif self.busy.locked():
            st.level, st.message = DiagnosticStatus.WARN, "restarting"
        else:
            st.level, st.message = DiagnosticStatus.OK, "supervising (%d restarts)" % self.restarts
        st.values = [KeyValue("restarts", str(self.restarts)), KeyValue("last stop", self.last_stop or "-"),
                     KeyValue("started pid", str(self.started_pid or "-")),
                     KeyValue("bad reports", str(self.bad_reports))]
        self.diag_pub.publish(DiagnosticArray(header=rospy.Header(stamp=rospy.Time.now()), status=[st]))

    def learn_pids(self):
        """Remembers the node's PID while it answers: a hung node cannot be asked."""
        while not rospy.is_shutdown():
            uri = node_uri(self.masters.get(), self.node)
            if uri is not None and uri != self.known[0] and local(uri):
                pid = ask_pid(uri, rospy.get_name())
                if pid is not None:
                    self.known = (uri, pid)
            time.sleep(0.2)

    def find_pid(self):
        uri = node_uri(self.masters.get(), self.node)
        if uri is None:
            return None
        if not local(uri):
            rospy.logwarn("hp_supervisor: %s runs on %s, not here: cannot restart it", self.node, uri)
            self.last_stop = "not stopped: runs on %s" % uri
            return None
        pid = ask_pid(uri, rospy.get_name())
        if pid is None and self.known[0] == uri:
            pid = self.known[1]  # it does not answer (hung): the PID it had when it did
        return pid

    def stop_running(self):
        pid = self.find_pid()
        if pid is None or not alive(pid):
            rospy.logwarn("hp_supervisor: %s is not running (crashed)", self.node)
            if self.last_stop is None:  # not set by find_pid: not a node elsewhere
                self.last_stop = "not running (crashed)"
            return
        rospy.logwarn("hp_supervisor: stopping %s (pid %d)", self.node, pid)
        os.kill(pid, signal.SIGTERM)
        self.last_stop = "SIGTERM"
        deadline = time.monotonic() + self.kill_grace_s
        while time.monotonic() < deadline and alive(pid):
            time.sleep(0.01)
        if alive(pid):
            rospy.logwarn("hp_supervisor: %s did not stop within %.1f s (hung): SIGKILL",
                          self.node, self.kill_grace_s)
            os.kill(pid, signal.SIGKILL)
            self.last_stop = "SIGKILL (hung)"
            while alive(pid):
                time.sleep(0.01)

    def start_new(self):
        found = roslib.packages.find_node(self.package, self.type)
        if not found:
            rospy.logerr("hp_supervisor: no executable %s in %s", self.type, self.package)
            self.failure = "no executable %s in %s" % (self.type, self.package)
            return
        ns, name = rosgraph.names.namespace(self.node), self.node.rstrip("/").rsplit("/", 1)[-1]
        child = subprocess.Popen([found[0], "__name:=" + name, "__ns:=" + ns])
        self.children.append(child)
        self.started_pid = child.pid
        self.failure = None
        self.restarts += 1
        rospy.logwarn("hp_supervisor: started %s again (pid %d, restart %d)", self.node,
                      child.pid, self.restarts)

    def restart(self):
        try:
            self.last_stop = None
            self.stop_running()
            if self.boot_delay_s > 0.0:
                rospy.sleep(self.boot_delay_s)
            if not rospy.is_shutdown():
                self.start_new()
        except rospy.ROSInterruptException:
            pass
        except Exception as e:  # noqa: BLE001  a restart that dies unseen leaves the HA flying on
            rospy.logerr("hp_supervisor: restarting %s failed: %s", self.node, e)
            self.failure = "restart failed: %s" % e
        finally:
            self.busy.release()

    def shutdown(self):
        for child in self.children:
            if child.poll() is None:
                child.terminate()
        for child in self.children:
            try:
                child.wait(timeout=3.0)
            except subprocess.TimeoutExpired:
                child.kill()
                child.wait()


def main():
    rospy.init_node("hp_supervisor")
    exit_promptly()
    supervisor = Supervisor()
    rospy.on_shutdown(supervisor.shutdown)
    rospy.spin()


if __name__ == "__main__":
    main()
