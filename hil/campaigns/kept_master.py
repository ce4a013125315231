"""A ROS master and its rosout node kept by a campaign's Dask worker for every flight it flies
(run_flight.py --master), rather than one started and stopped per flight: 0.3-0.4 s of CPU a
flight instead of the 0.9-1.0 s a master and rosout of the flight's own cost (hil/README.md).

A Dask worker plugin: setup() starts rosmaster and rosout when the campaign registers the plugin,
teardown() stops them when it unregisters it or the worker closes. ensure() is what a flight's
task asks for the master's URI: a master or rosout that has died since is started anew (a new
port). The processes hold the campaign's token (CAMPAIGN_VAR), so the campaign can sweep any a
worker that died left, and die with the worker's thread that started them (setpriv
--pdeathsig), so a worker killed outright leaves none. One flight at a time per master: the
plugin's worker runs one task at a time (threads_per_worker=1)."""
import os
import shutil
import signal
import subprocess
import tempfile
import time

PLUGIN_NAME = "hil-kept-master"
CAMPAIGN_VAR = "HIL_CAMPAIGN"
UP_BOUND_S = 60.0


class KeptMaster:
    """Duck-typed distributed.WorkerPlugin (setup, teardown); usable without Dask too."""

    def __init__(self, campaign_token):
        self.token = campaign_token
        self.uri = None
        self.procs = []
        self.folder = None
        self.ready = False

    def setup(self, worker=None):
        # Never raises: Dask would fail the campaign's registration of the plugin with it. A master
        # that cannot be started now is tried again, and reported, by ensure() at each flight.
        try:
            self.start()
        except (RuntimeError, OSError):
            self.stop()

    def teardown(self, worker=None):
        self.stop()

    def start(self):
        """rosmaster on a free loopback port and rosout, started, not waited for (setup runs on
        the worker's event loop; ensure() waits)."""
        from stack_tools.ports import free_port
        from roslib.packages import find_node
        self.stop()
        rosout = find_node("rosout", "rosout")
        if not rosout:
            raise RuntimeError("the rosout node is not installed (package rosout)")
        self.folder = tempfile.mkdtemp(prefix="hil-master-")
        port = free_port()
        self.uri = "http://127.0.0.1:%d" % port
        env = dict(os.environ, ROS_MASTER_URI=self.uri, ROS_HOSTNAME="127.0.0.1", ROS_IP="127.0.0.1",
                   ROS_HOME=self.folder, ROS_LOG_DIR=os.path.join(self.folder, "log"))
        env[CAMPAIGN_VAR] = self.token
        env.pop("ROS_NAMESPACE", None)
        for name, argv in (("rosmaster", ["rosmaster", "--core", "-p", str(port), "-w", "3"]),
                           ("rosout", [rosout[0], "__name:=rosout"])):
            with open(os.path.join(self.folder, name + ".log"), "w") as log:
                try:
                    self.procs.append(subprocess.Popen(
                        ["setpriv", "--pdeathsig", "TERM"] + argv, env=env, stdout=log, stderr=subprocess.STDOUT,
                        stdin=subprocess.DEVNULL, start_new_session=True))
                except OSError:
                    self.stop()  # the master without its rosout is no master for a flight
                    raise
        self.ready = False

    def alive(self):
        return bool(self.procs) and all(p.poll() is None for p in self.procs)

    def ensure(self):
        """The master's URI once it answers with roscore's parameters set; started anew first
        when it or rosout has died. RuntimeError when it does not come up within UP_BOUND_S."""
        from hil import ros_master
        if not self.alive():
            self.start()
        if not self.ready:
            deadline = time.monotonic() + UP_BOUND_S
            while not ros_master.answers(self.uri):
                if time.monotonic() > deadline or not self.alive():
                    self.stop()
                    raise RuntimeError("the worker's ROS master did not come up")
                time.sleep(0.05)
            ros_master.set_core_parameters(self.uri, ros_master.core_parameters())
            self.ready = True
        return self.uri

    def stop(self):
        """rosout, then the master: SIGINT, SIGKILL past 10 s; their folder removed."""
        for p in reversed(self.procs):
            if p.poll() is None:
                try:
                    os.killpg(p.pid, signal.SIGINT)
                except ProcessLookupError:
                    pass
            try:
                p.wait(timeout=10.0)
            except subprocess.TimeoutExpired:
                os.killpg(p.pid, signal.SIGKILL)
                p.wait()
        self.procs = []
        self.ready = False
        if self.folder:
            shutil.rmtree(self.folder, ignore_errors=True)
            self.folder = None
