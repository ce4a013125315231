"""hp_supervisor reads each /decision_status as bytes, at the one byte of restart_requested, not
decoded whole (a hundred reports a simulated second, in a lockstep flight over a thousand a wall
second). These say the byte it reads is that field whatever the other fields hold, and that a
report of another length is ignored, not read at a wrong place."""
import importlib.util
import io
import os
import random

import rospy
from drone_ros.msg import DecisionStatus

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scripts", "hp_supervisor.py")


def supervisor_module():
    spec = importlib.util.spec_from_file_location("hp_supervisor", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def raw(msg):
    buf = io.BytesIO()
    msg.serialize(buf)
    m = rospy.AnyMsg()
    m._buff = buf.getvalue()
    return m


def report(rng, requested):
    return DecisionStatus(stamp=rospy.Time(rng.randrange(1 << 32), rng.randrange(10 ** 9)),
                          controller=rng.randrange(256), reasons=rng.randrange(1 << 32),
                          reasons_at_switch=rng.randrange(1 << 32), restart_count=rng.randrange(1 << 16),
                          restart_requested=requested, last_seq=rng.randrange(1 << 32),
                          stable_for_s=rng.uniform(-1e3, 1e3), airspeed_ftps=rng.uniform(-1e3, 1e3))


class Recorder:
    def __init__(self, cls):
        self.sup = cls.__new__(cls)  # no node: on_report only hands the flag on
        self.seen = []
        self.sup.on_request = self.seen.append
        self.sup.bad_reports = 0


def test_the_byte_read_is_restart_requested_whatever_the_other_fields_hold():
    hs = supervisor_module()
    rec = Recorder(hs.Supervisor)
    rng = random.Random(5)
    wanted = [rng.random() < 0.5 for _ in range(500)]
    for w in wanted:
        rec.sup.on_report(raw(report(rng, w)))
    assert rec.seen == wanted


def test_a_report_of_another_length_is_ignored():
    hs = supervisor_module()
    rec = Recorder(hs.Supervisor)
    whole = raw(DecisionStatus(restart_requested=True))._buff
    for cut in (whole[:-1], whole + b"\x01", b""):
        m = rospy.AnyMsg()
        m._buff = cut
        rec.sup.on_report(m)
    assert rec.seen == []
    assert rec.sup.bad_reports == 3
    m = rospy.AnyMsg()
    m._buff = whole
    rec.sup.on_report(m)
    assert rec.seen == [True]
