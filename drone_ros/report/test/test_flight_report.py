"""flight_report run as a person runs it (the built `rosrun drone_ros flight_report` executable)
on bags of a scripted flight: HP flying, a crash, the HA taking over with REASON_NO_COMMAND,
RECOVERING, back to the HP. Also its CSV export (--export csv), read back with the csv module."""
import csv
import os
import struct
import subprocess
from html.parser import HTMLParser

import pytest


import scripted_flight  # noqa: E402
from drone_ros.msg import DecisionStatus  # noqa: E402
from report_core import definitions  # noqa: E402

FIGURES = ("fig5_3_outputs.png", "fig5_4_accelerations.png", "fig5_5_euler_angles.png",
           "fig5_6_body_rates.png", "fig5_7_velocity.png", "track.png", "altitude.png",
           "airspeed.png", "link_timing.png")
# The labels the page gives each controller (figures.CONTROLLER_LABELS).
LABELS = {DecisionStatus.CONTROLLER_HP: "HP", DecisionStatus.CONTROLLER_HA: "HA",
          DecisionStatus.CONTROLLER_RECOVERING: "recovering"}


def tool():
    path = os.path.join(os.environ["DRONE_ROS_WS"], "devel", "lib", "drone_ros", "flight_report")
    assert os.access(path, os.X_OK), "build the workspace first: %s is missing" % path
    return path


def run(*args):
    return subprocess.run([tool(), *args], capture_output=True, text=True, timeout=300)


class _Tables(HTMLParser):
    """The rows of the table with id="switches", as cell texts."""

    def __init__(self):
        super().__init__()
        self.rows, self.images, self._in, self._cell = [], [], False, None

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if tag == "table":
            self._in = attrs.get("id") == "switches"
        elif tag == "img":
            self.images.append(attrs["src"])
        elif self._in and tag == "tr":
            self.rows.append([])
        elif self._in and tag == "td":
            self._cell = ""

    def handle_endtag(self, tag):
        if tag == "table":
            self._in = False
        elif self._in and tag == "td":
            self.rows[-1].append(self._cell.strip())
            self._cell = None

    def handle_data(self, data):
        if self._cell is not None:
            self._cell += data


def page(index_path):
    parser = _Tables()
    with open(index_path) as f:
        text = f.read()
    parser.feed(text)
    return text, [row for row in parser.rows if row]


def png_size(path):
    with open(path, "rb") as f:
        head = f.read(24)
    assert head[:8] == b"\x89PNG\r\n\x1a\n", "%s is not a PNG" % path
    return struct.unpack(">II", head[16:24])


def expected_switches():
    out = []
    previous = DecisionStatus.CONTROLLER_HP
    times = [s[0] for s in scripted_flight.SWITCHES] + [scripted_flight.LAST_DECISION_S]
    for i, (t_s, to, reasons) in enumerate(scripted_flight.SWITCHES):
        out.append((t_s, LABELS[previous], LABELS[to], reasons, times[i + 1] - t_s))
        previous = to
    return out


@pytest.fixture(scope="module")
def hil_flight(tmp_path_factory):
    """A HiL output folder as hil/HIL_INTERFACES.md section 4 lays it out, the report in report/."""
    folder = tmp_path_factory.mktemp("out") / "2026-11-23_101500-DG808-7"
    folder.mkdir()
    bag = folder / "flight.bag"
    scripted_flight.write(str(bag), with_truth=True)
    result = run(str(bag))
    assert result.returncode == 0, result.stderr
    assert "Traceback" not in result.stderr
    return folder / "report"


def test_hil_report_has_every_figure_and_links_them_from_the_page(hil_flight):
    text, _ = page(hil_flight / "index.html")
    parser = _Tables()
    parser.feed(text)
    for name in FIGURES:
        path = hil_flight / name
        assert path.exists(), name
        width, height = png_size(path)
        assert width >= 800 and height >= 450, name
        assert path.stat().st_size > 20000, "%s looks empty (%d bytes)" % (name, path.stat().st_size)
        assert name in parser.images, "%s is not on the page" % name


def test_switch_list_matches_the_scripted_crash_takeover_and_hand_back(hil_flight):
    _, rows = page(hil_flight / "index.html")
    expected = expected_switches()
    assert len(rows) == len(expected), rows
    for row, (t_s, from_label, to_label, reasons, duration_s) in zip(rows, expected):
        number, time_cell, from_cell, to_cell, reason_cell, duration_cell = row
        # The decisions are stamped 2 ms after the period starts (scripted_flight).
        assert float(time_cell) == pytest.approx(t_s + 0.002, abs=0.006), row
        assert (from_cell, to_cell) == (from_label, to_label), row
        named = definitions.bit_names(reasons, {DecisionStatus.REASON_NO_COMMAND: "NO_COMMAND"})
        if named:
            assert reason_cell == ", ".join(named), row
        else:
            assert reason_cell.startswith("none"), row
        assert float(duration_cell.split()[0]) == pytest.approx(duration_s, abs=0.011), row
    assert "until the end of the log" in rows[-1][5]
    assert "HP command valid for 2.00 s" in rows[-1][4]


def test_lockstep_log_keeps_the_simulators_clock_from_zero(tmp_path):
    """The simulator's clock starts at 0, so the first stamps are 0.0 (ROS's "unset" elsewhere);
    the recorder receives on the wall clock, and the mission plan carries no stamp at all."""
    folder = tmp_path / "2026-11-23_101500-DG808-3"
    folder.mkdir()
    scripted_flight.write(str(folder / "flight.bag"), with_truth=True, t0_s=0.0,
                          received_after_s=1.795e9)
    result = run(str(folder / "flight.bag"))
    assert result.returncode == 0, result.stderr
    text, rows = page(folder / "report" / "index.html")
    expected = expected_switches()
    assert [float(row[1]) for row in rows] == pytest.approx(
        [t_s + 0.002 for t_s, *_ in expected], abs=0.006), rows
    assert float(rows[-1][5].split()[0]) == pytest.approx(expected[-1][4], abs=0.011), rows
    assert "%.1f s" % scripted_flight.LAST_DECISION_S in text or \
        "%.1f s" % scripted_flight.END_S in text


def test_a_time_sync_that_sets_the_has_clock_back_keeps_one_switch_per_switch(tmp_path):
    """A loaded lockstep HiL: rosserial's time sync sets the HA's clock back 60 ms just before
    the takeover and just before the hand-back, so the periods around each step carry the same
    stamps twice. The page lists the three switches the HA made, each at the time its own stamp
    says (held while the clock catches up), not the HP/HA flapping a sort by stamp reads."""
    folder = tmp_path / "2026-12-06_203000-DG808-3"
    folder.mkdir()
    scripted_flight.write(str(folder / "flight.bag"), with_truth=True, t0_s=0.0, received_after_s=1.795e9,
                          ha_clock_steps=((30.02, -0.06), (46.98, -0.06)))
    result = run(str(folder / "flight.bag"))
    assert result.returncode == 0, result.stderr
    _, rows = page(folder / "report" / "index.html")
    expected = expected_switches()
    assert [(row[2], row[3]) for row in rows] == [(f, t) for _, f, t, *_ in expected], rows
    assert [float(row[1]) for row in rows] == pytest.approx(
        [t_s + 0.002 - 0.06 for t_s, *_ in expected], abs=0.061), rows


def test_hil_report_draws_truth_and_names_its_source(hil_flight):
    text, _ = page(hil_flight / "index.html")
    assert "No simulator truth" not in text
    assert "simulator truth" in text


def test_real_flight_without_truth_reports_measured_state_and_says_so(tmp_path):
    bag = tmp_path / "2026-11-23_120000-DG808-flight.bag"
    scripted_flight.write(str(bag), with_truth=False)
    result = run(str(bag), "--out", str(tmp_path / "r"))
    assert result.returncode == 0, result.stderr
    text, rows = page(tmp_path / "r" / "index.html")
    assert "No simulator truth (/hil/truth) in this log" in text
    assert [(r[2], r[3]) for r in rows] == [(s[1], s[2]) for s in expected_switches()]
    for name in FIGURES:
        assert (tmp_path / "r" / name).stat().st_size > 20000, name


def test_real_flight_track_is_drawn_around_the_has_home_when_the_log_has_it(tmp_path):
    # The scripted flight's first fix is 1500 ft north of home: drawn around the first fix (the
    # old rule), the track would start at 0 and lie 1500 ft off the mission's waypoints.
    import importlib.machinery
    import types
    script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scripts", "flight_report")
    loader = importlib.machinery.SourceFileLoader("flight_report_tool", script)
    module = types.ModuleType(loader.name)
    module.__file__ = script
    loader.exec_module(module)
    from report_core.flight_log import FlightLog
    bag = tmp_path / "2026-11-23_120000-DG808-flight.bag"
    for with_home, first_north_ft, said in ((True, 1500.0, "home = the HA's /home"),
                                            (False, 0.0, "no /home recorded")):
        scripted_flight.write(str(bag), with_truth=False, with_home=with_home)
        log = FlightLog(*module.read_bag(str(bag)))
        _, north, east, _, source = log.position()
        assert north[0] == pytest.approx(first_north_ft, abs=5.0), with_home
        assert said in source, source


def test_the_flight_log_records_the_stacks_home():
    import xml.etree.ElementTree as ET
    root = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
    args = ET.parse(os.path.join(root, "launch", "record.launch")).getroot().find("node").get("args")
    assert "home" in args.split()  # relative: /home from the root namespace, /uav1/home in uav1
    from hil import run_flight
    assert "/home" in run_flight.BAG_TOPICS


def test_aircraft_unknown_from_the_name_asks_for_it(tmp_path):
    bag = tmp_path / "flight.bag"
    scripted_flight.write(str(bag), end_s=2.0)
    result = run(str(bag))
    assert result.returncode == 2
    assert "--aircraft" in result.stderr and "Traceback" not in result.stderr
    result = run(str(bag), "--aircraft", "DG808", "--out", str(tmp_path / "r"))
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "r" / "index.html").exists()


def test_a_file_that_is_not_a_bag_gets_a_clear_error(tmp_path):
    bag = tmp_path / "2026-11-23_120000-DG808-flight.bag"
    bag.write_bytes(b"this is not a bag\n" * 100)
    result = run(str(bag), "--out", str(tmp_path / "r"))
    assert result.returncode == 2
    assert "cannot read" in result.stderr and "Traceback" not in result.stderr
    assert not (tmp_path / "r" / "index.html").exists()


def test_a_truncated_bag_gets_a_clear_error_naming_the_fix(tmp_path):
    bag = tmp_path / "2026-11-23_120000-DG808-flight.bag"
    scripted_flight.write(str(bag), end_s=10.0)
    raw = bag.read_bytes()
    bag.write_bytes(raw[: len(raw) // 2])
    result = run(str(bag), "--out", str(tmp_path / "r"))
    assert result.returncode == 2
    assert "rosbag reindex" in result.stderr and "Traceback" not in result.stderr


def test_a_bag_without_decisions_says_which_topic_is_missing(tmp_path):
    import rosbag
    from drone_ros.msg import pwm
    bag_path = tmp_path / "2026-11-23_120000-DG808-flight.bag"
    with rosbag.Bag(str(bag_path), "w") as bag:
        bag.write("/pwm", pwm())
    result = run(str(bag_path), "--out", str(tmp_path / "r"))
    assert result.returncode == 2
    assert "/decision_status" in result.stderr and "Traceback" not in result.stderr


def test_reason_names_come_from_the_message_definition():
    names = definitions.constants(DecisionStatus._full_text, "REASON_")
    declared = {getattr(DecisionStatus, a): a[len("REASON_"):] for a in dir(DecisionStatus)
                if a.startswith("REASON_")}
    assert names == declared
    # A reason a newer HA sends is shown by value, never dropped.
    assert definitions.bit_names(DecisionStatus.REASON_STALL | (1 << 20), names) == [
        "STALL", "unnamed bit 0x100000"]


# ------------------------------------------------------------------------- --export csv

def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], [dict(zip(rows[0], row)) for row in rows[1:]]


def test_csv_export_writes_si_columns_named_with_their_units(tmp_path):
    """One message per stream with known values in the bag's units (feet, ft/s, g) at known ROS
    times: each comes back converted, in a column named with its unit."""
    import rosbag
    import rospy
    from drone_ros.msg import HilTruth, ServoCommand, data
    bag_path = tmp_path / "flight.bag"
    t0 = 1795000000.25  # a real flight's stamps: wall time
    with rosbag.Bag(str(bag_path), "w") as bag:
        d = data()
        d.header.stamp = rospy.Time.from_sec(t0)
        d.lla.x, d.lla.y, d.lla.z = 38.9717, -95.2353, 250.5
        d.angle.x = 0.25
        d.velocity.x = 17.0
        d.acceleration.z = -1.0  # g
        d.air_velocity = 100.0  # ft/s
        d.a_usbstatus = d.v_usbstatus = 1
        bag.write("/data", d, d.header.stamp)
        status = DecisionStatus(stamp=rospy.Time.from_sec(t0 + 0.5), controller=DecisionStatus.CONTROLLER_HA,
                                reasons=DecisionStatus.REASON_NO_COMMAND | DecisionStatus.REASON_STALL,
                                last_seq=41, airspeed_ftps=50.0, altitude_agl_ft=1000.0, elevator_deg=-1.5)
        bag.write("/decision_status", status, status.stamp)
        cmd = ServoCommand(seq=7, stamp=rospy.Time.from_sec(t0 + 1.0), throttle=0.5, aileron_deg=3.25)
        bag.write("/servo_op", cmd, cmd.stamp)
        truth = HilTruth(north_ft=1000.0, height_above_home_ft=400.0, airspeed_ftps=60.0,
                         accel_z_ft_s2=-32.0, roll_deg=20.0)
        truth.header.stamp = rospy.Time.from_sec(t0 + 2.0)
        bag.write("/hil/truth", truth, truth.header.stamp)
    out = tmp_path / "csv"
    result = run(str(bag_path), "--export", "csv", "--out", str(out))
    assert result.returncode == 0, result.stderr
    assert sorted(os.listdir(out)) == ["decision.csv", "ins.csv", "servo_commands.csv", "truth.csv"]

    header, rows = read_csv(out / "ins.csv")
    assert header[:6] == ["t_s", "ros_time_s", "lat_deg", "lon_deg", "alt_m", "roll_rad"]
    assert {"airspeed_mps", "v_north_mps", "accel_z_mps2", "p_rad_s", "ha_link_up"} <= set(header)
    (ins,) = rows
    assert float(ins["t_s"]) == 0.0  # the first message of the flight
    assert float(ins["ros_time_s"]) == pytest.approx(t0, abs=1e-6)
    assert float(ins["airspeed_mps"]) == pytest.approx(30.48, abs=1e-9)  # 100 ft/s
    assert float(ins["accel_z_mps2"]) == pytest.approx(-9.80665, abs=1e-9)  # -1 g
    assert (float(ins["lat_deg"]), float(ins["alt_m"]), float(ins["roll_rad"])) == (38.9717, 250.5, 0.25)
    assert float(ins["v_north_mps"]) == 17.0 and ins["ha_link_up"] == "1"

    header, (decision,) = read_csv(out / "decision.csv")
    assert {"altitude_agl_m", "airspeed_mps", "elevator_deg", "controller_name", "reason_names"} <= set(header)
    assert float(decision["t_s"]) == pytest.approx(0.5, abs=1e-6)
    assert float(decision["altitude_agl_m"]) == pytest.approx(304.8, abs=1e-9)  # 1000 ft
    assert float(decision["airspeed_mps"]) == pytest.approx(15.24, abs=1e-9)  # 50 ft/s
    assert (decision["controller"], decision["controller_name"]) == ("1", "HA")
    assert decision["reason_names"] == "NO_COMMAND|STALL"
    assert decision["last_seq"] == "41" and float(decision["elevator_deg"]) == -1.5

    _, (command,) = read_csv(out / "servo_commands.csv")
    assert float(command["t_s"]) == pytest.approx(1.0, abs=1e-6)
    assert command["seq"] == "7" and float(command["aileron_deg"]) == 3.25

    _, (state,) = read_csv(out / "truth.csv")
    assert float(state["north_m"]) == pytest.approx(304.8, abs=1e-9)
    assert float(state["height_above_home_m"]) == pytest.approx(121.92, abs=1e-9)
    assert float(state["airspeed_mps"]) == pytest.approx(18.288, abs=1e-9)
    assert float(state["accel_z_mps2"]) == pytest.approx(-9.7536, abs=1e-9)  # -32 ft/s^2
    assert float(state["roll_deg"]) == 20.0


def test_csv_export_of_a_whole_flight_has_a_row_per_message_on_the_reports_time_axis(hil_flight, tmp_path):
    import rosbag
    bag_path = hil_flight.parent / "flight.bag"
    result = run(str(bag_path), "--export", "csv", "--out", str(tmp_path / "csv"))
    assert result.returncode == 0, result.stderr
    with rosbag.Bag(str(bag_path)) as bag:
        counts = {topic: bag.get_message_count(topic) for topic in
                  ("/data", "/hil/truth", "/servo_op", "/decision_status")}
    for name, topic in (("ins", "/data"), ("truth", "/hil/truth"), ("servo_commands", "/servo_op"),
                        ("decision", "/decision_status")):
        _, rows = read_csv(tmp_path / "csv" / (name + ".csv"))
        assert len(rows) == counts[topic], name
        times = [float(r["t_s"]) for r in rows]
        assert times == sorted(times) and 0.0 <= times[0] < 0.01 and times[-1] < scripted_flight.END_S
    _, rows = read_csv(tmp_path / "csv" / "decision.csv")
    took_over = next(r for r in rows if r["controller_name"] == "HA")
    assert float(took_over["t_s"]) == pytest.approx(scripted_flight.SWITCHES[0][0], abs=0.011)
    assert took_over["reason_names"] == "NO_COMMAND"


def test_csv_export_of_a_missing_bag_or_one_without_the_streams_says_so(tmp_path):
    import rosbag
    from drone_ros.msg import pwm
    result = run(str(tmp_path / "nowhere.bag"), "--export", "csv")
    assert result.returncode == 2
    assert "no such file" in result.stderr and "nowhere.bag" in result.stderr
    assert "Traceback" not in result.stderr
    bag_path = tmp_path / "flight.bag"
    with rosbag.Bag(str(bag_path), "w") as bag:
        bag.write("/pwm", pwm())
    result = run(str(bag_path), "--export", "csv", "--out", str(tmp_path / "csv"))
    assert result.returncode == 2
    assert "nothing to export" in result.stderr and "/decision_status" in result.stderr
    assert "Traceback" not in result.stderr
    assert not (tmp_path / "csv").exists()
