"""The simulator's native lockstep node (hil/native/lockstep_io.cpp through hil.lockstep_io) at
its ROS interface, under a master of the test's own: it counts what each topic the step waits for
delivers (the arduino node's link-down /pwm aside), gives the newest command's seq and the whole
command, keeps the controller's waypoint changes (/to_hil) at the stamps of the steps that made them, publishes /clock and /hil/lockstep as LockstepStep declares them, and refuses a second
node in one process. The preflight's check that every node on simulated time is served /clock
is asked of it too. The flights (test_determinism and every lockstep test) fly on it too."""
import json
import os
import subprocess
import sys

from stack_testing.ros_master import private_master

HERE = os.path.dirname(os.path.abspath(__file__))


def test_the_native_node_counts_what_the_step_waits_for_and_declares_the_step():
    with private_master() as env:
        env = dict(env, ROS_NAMESPACE="/flight_a")
        r = subprocess.run([sys.executable, os.path.join(HERE, "lockstep_io_node.py")], env=env,
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=120)
    assert r.returncode == 0, r.stderr.decode(errors="replace")[-3000:]
    out = json.loads(r.stdout.decode().strip().splitlines()[-1])
    assert out["name"] == "/flight_a/hil_sim_io"
    assert out["second_node_refused"]
    assert out["before"] == {"vn": 0, "status": 0, "pwm": 0, "home": 0, "servo_op": 0, "to_hil": 0}
    assert out["waypoints_before"] == []
    assert out["wait_for_none"] is False
    assert out["latest_seq_before"] is None
    assert all(out["waited"].values()), out["waited"]
    assert out["after"] == {"vn": 4, "status": 2, "pwm": 3, "home": 1, "servo_op": 2, "to_hil": 7}
    assert out["waypoints"] == [[0.01, 0], [0.03, 1], [0.05, 2], [0.06, 0]]
    assert out["latest_seq"] == 42
    assert out["latest"] == [42, -2.5, 0.5, 0xDEADBEEF]
    assert out["clock"] == [1230000000]
    assert out["clock_served"] and not out["clock_served_with_late_node"] and out["clock_served_after_it_went"]
    assert out["lockstep"] == [[1230000000, 4, 4, 4, 4, 4, 3, 3, 1, 0]]
    assert out["after_close"] == 0  # a closed node answers nothing
    assert out["waypoints_after_close"] == []
