"""Every HP node started with a bad private parameter refuses it before it opens a port or
advertises, the same way: exit status 2 and `<node>: bad parameter: <the parameter, and why>` on
its log, so a node launched required="true" ends the launch with the reason on screen."""
import glob
import os
import subprocess

import pytest


def _built(pattern):
    return os.path.join(os.environ.get("DRONE_ROS_WS", ""), "devel", "lib", "drone_ros", pattern)


# controller_<aircraft>: whichever aircraft the workspace was built for.
CONTROLLER = os.path.basename((glob.glob(_built("controller_*")) or ["controller_DG808"])[0])


@pytest.mark.parametrize("node,arg,named", [
    ("vn200", "_baud:=100000", "~baud"),
    ("arduino", "_baud:=1200", "~baud 1200 would erase the Due's sketch"),
    ("microhard_gs", "_transport:=pigeon", "transport must be udp or serial, not pigeon"),
    (CONTROLLER, "_dt:=5", "dt = 5 is outside"),
])
def test_a_bad_parameter_ends_the_node_with_status_2_and_names_it(master, node, arg, named):
    exe = _built(node)
    # A node name of its own per case: private parameters stay on the master between runs.
    name = "bad_parameter_" + "".join(c for c in node + arg if c.isalnum())
    r = subprocess.run([exe, "__name:=" + name, arg], env=master, capture_output=True, text=True,
                       timeout=60)
    log = r.stdout + r.stderr
    assert r.returncode == 2, log
    assert "%s: bad parameter: " % node in log and named in log, log
