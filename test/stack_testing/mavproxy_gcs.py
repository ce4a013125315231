"""MAVProxy as the operator runs it, for the tests (a helper, not a test).

Runs the pinned MAVProxy (microhard_gs/requirements.txt) headless: no console, no map, commands
typed on its standard input as a user would type them, its output collected line by line. It
listens on a loopback UDP port (`udpin:127.0.0.1:PORT`, or another loopback address: a ground
station on another machine), the port the node sends to. HOME is a
private directory, so nothing of the user's MAVProxy or pymavlink set-up is read, and it holds
the mode-name map the project ships for pymavlink-based ground stations. Every process started
here is stopped by stop().
"""
import os
import queue
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time

from stack_tools.paths import ROOT

MODE_MAP = os.path.join(ROOT, "microhard_gs", "gcs", "pymavlink_custom_mode_map.json")
# MAVProxy's default modules less the terrain one (it fetches elevation tiles from the internet
# when asked for terrain; tests stay on loopback).
MODULES = "log,signing,wp,rally,fence,ftp,param,relay,tuneopt,arm,mode,calibration,rc,auxopt,misc,cmdlong,battery,output,adsb,layout"


class MavProxy:
    def __init__(self, udp_port, mode_map=True, host="127.0.0.1"):
        self.home = tempfile.mkdtemp(prefix="mavproxy_gcs_")
        if mode_map:
            os.makedirs(os.path.join(self.home, ".pymavlink"))
            shutil.copy(MODE_MAP, os.path.join(self.home, ".pymavlink", "custom_mode_map.json"))
        self.lines = []
        self._new = queue.Queue()
        env = dict(os.environ, HOME=self.home)
        env.pop("DISPLAY", None)
        exe = os.path.join(os.path.dirname(sys.executable), "mavproxy.py")
        self.proc = subprocess.Popen(
            [sys.executable, exe, "--master=udpin:%s:%d" % (host, udp_port), "--source-system=255",
             "--state-basedir=" + self.home, "--default-modules=" + MODULES],
            stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, env=env,
            cwd=self.home, start_new_session=True)
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self):
        for raw in self.proc.stdout:
            line = raw.decode(errors="replace").rstrip()
            self.lines.append(line)
            self._new.put(line)

    def mark(self):
        """A position in the output; wait_for(..., since=mark) looks only after it."""
        return len(self.lines)

    def command(self, text):
        self.proc.stdin.write((text + "\n").encode())
        self.proc.stdin.flush()

    def wait_for(self, needle, timeout_s=20.0, since=0):
        """The first output line after `since` containing `needle`, or None."""
        deadline = time.time() + timeout_s
        seen = since
        while True:
            for line in self.lines[seen:]:
                seen += 1
                if needle in line:
                    return line
            if time.time() >= deadline:
                return None
            try:
                self._new.get(timeout=0.1)
            except queue.Empty:
                pass

    def output(self, since=0):
        return "\n".join(self.lines[since:])

    def stop(self):
        if self.proc.poll() is None:
            try:
                self.proc.stdin.close()  # end of input: MAVProxy leaves its input loop
            except OSError:
                pass
            try:
                self.proc.wait(timeout=5)
            except subprocess.TimeoutExpired:
                os.killpg(self.proc.pid, signal.SIGTERM)
                try:
                    self.proc.wait(timeout=5)
                except subprocess.TimeoutExpired:
                    os.killpg(self.proc.pid, signal.SIGKILL)
                    self.proc.wait(timeout=5)
        shutil.rmtree(self.home, ignore_errors=True)


def write_qgc_wpl(path, rows):
    """A `QGC WPL 110` waypoint file as MAVProxy and QGroundControl write them: one row per item,
    seq, current, frame, command, p1..p4, lat, lon, alt, autocontinue (tab separated)."""
    with open(path, "w") as f:
        f.write("QGC WPL 110\n")
        for seq, (current, frame, command, lat, lon, alt) in enumerate(rows):
            f.write("\t".join([str(seq), str(current), str(frame), str(command), "0", "0", "0", "0",
                               "%.7f" % lat, "%.7f" % lon, "%.3f" % alt, "1"]) + "\n")


def read_qgc_wpl(path):
    """Rows (frame, command, lat, lon, alt) of a `QGC WPL 110` file."""
    with open(path) as f:
        lines = f.read().splitlines()
    assert lines[0].startswith("QGC WPL 110"), lines[0]
    rows = []
    for line in lines[1:]:
        c = line.split("\t")
        rows.append((int(c[2]), int(c[3]), float(c[8]), float(c[9]), float(c[10])))
    return rows
