"""A ground station on another machine (issue 27): run_flight.py --gcs-host/--gcs-port send the
vehicle's telemetry where a lab's QGroundControl listens, and the vehicle answers it from the port
it was given. The "other machine" is 127.0.0.2 (loopback, but another address than the vehicle's):
a pymavlink link listening there as QGroundControl does (udpin) hears the HEARTBEATs and positions
of a lockstep flight and gets a parameter back when it asks for one; MAVProxy, run there as an
operator runs it, sees the vehicle come online and downloads the mission the flight flies."""
import contextlib
import os
import socket
import subprocess
import sys
import tempfile
import threading

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
os.environ.setdefault("MAVLINK20", "1")
from pymavlink import mavutil  # noqa: E402  (MAVLINK20 must be set first)

from hil.campaigns.flight import run_completed  # noqa: E402

from stack_testing.mavproxy_gcs import MavProxy, read_qgc_wpl  # noqa: E402

GCS_HOST = "127.0.0.2"


def free_udp_port(host):
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
        s.bind((host, 0))
        return s.getsockname()[1]


@contextlib.contextmanager
def flying_in_background(duration_s, gcs_port, vehicle_port):
    """A lockstep flight whose ground station is GCS_HOST:gcs_port, flown in a thread (given to
    see whether it still flies) while the test plays the ground station; waited for on the way
    out, and it must have ended well."""
    folder = os.path.join(tempfile.mkdtemp(prefix="hil_gcs_"), "flight")
    result = {}

    def fly():
        result["r"] = run_completed([sys.executable, os.path.join(ROOT, "hil", "run_flight.py"),
                                     "--duration", str(duration_s), "--fault", "none", "--no-bag", "--quiet",
                                     "--folder", folder, "--gcs-host", GCS_HOST, "--gcs-port", str(gcs_port),
                                     "--vehicle-port", str(vehicle_port)], timeout=600)
    flight = threading.Thread(target=fly)
    flight.start()
    try:
        yield flight
    finally:
        flight.join(timeout=600)
    r = result["r"]
    assert r.returncode == 0, r.stdout.decode(errors="replace")[-3000:]


def test_a_ground_station_at_another_address_hears_the_vehicle_and_is_answered():
    gcs_port, vehicle_port = free_udp_port(GCS_HOST), free_udp_port("127.0.0.1")
    gcs = mavutil.mavlink_connection("udpin:%s:%d" % (GCS_HOST, gcs_port), source_system=255)
    with contextlib.closing(gcs), flying_in_background(30, gcs_port, vehicle_port) as flight:
        seen = {}
        while flight.is_alive() and not ({"HEARTBEAT", "GLOBAL_POSITION_INT"} <= set(seen)):
            m = gcs.recv_match(type=["HEARTBEAT", "GLOBAL_POSITION_INT"], blocking=True, timeout=1.0)
            if m is not None and m.get_srcSystem() == 1:
                seen[m.get_type()] = m
        assert {"HEARTBEAT", "GLOBAL_POSITION_INT"} <= set(seen), "the vehicle sent nothing to %s:%d" % (
            GCS_HOST, gcs_port)
        # From the port it was given, which a ground station's link is configured with.
        assert gcs.clients == {("127.0.0.1", vehicle_port)}, gcs.clients
        # Asked back (udpin answers the address it heard the vehicle from), the vehicle answers.
        answer = None
        for _ in range(10):
            gcs.mav.param_request_read_send(1, 1, b"", 0)
            answer = gcs.recv_match(type="PARAM_VALUE", blocking=True, timeout=1.0)
            if answer is not None or not flight.is_alive():
                break
        assert answer is not None, "no PARAM_VALUE back to the ground station at %s" % GCS_HOST
        assert answer.param_count > 0


def test_mavproxy_at_another_address_sees_the_vehicle_online_and_downloads_its_mission():
    gcs_port, vehicle_port = free_udp_port(GCS_HOST), free_udp_port("127.0.0.1")
    mavproxy = MavProxy(gcs_port, host=GCS_HOST)
    with contextlib.ExitStack() as on_exit:
        on_exit.callback(mavproxy.stop)
        flight = on_exit.enter_context(flying_in_background(40, gcs_port, vehicle_port))
        assert mavproxy.wait_for("online system 1", 300) is not None, mavproxy.output()[-3000:]
        # The simulator uploads the case study's mission once the stack is up; listed until then.
        # Asked again every 2 s, as a ground station retries: in CI under load (2026-12-06) MAVProxy
        # listed 0 waypoints at connect and printed nothing for the next `wp list`, and a 15 s wait
        # outlived the flight. Why is not known: microhard_gs answers a list at once, upload or not
        # (MissionService::on_request_list).
        rows = None
        while flight.is_alive() and not rows:
            mark = mavproxy.mark()
            mavproxy.command("wp list")
            # Its parameters' "Saved 24 parameters to ..." may come first: waited past.
            saved = mavproxy.wait_for(" waypoints to ", 2, since=mark)
            if saved is not None:
                # Every row: the vehicle's items are the waypoints from seq 0, no home row
                # (the simulator uploads as QGroundControl does: microhard_gs/README.md, "Item 0 as home").
                rows = read_qgc_wpl(saved.split(" to ", 1)[1].strip())
        assert rows, "MAVProxy at %s got no mission: %s" % (GCS_HOST, mavproxy.output()[-3000:])
        flown = read_qgc_wpl(os.path.join(ROOT, "aircraft", "DG808", "missions", "case_study.waypoints"))[1:]
        assert [(round(r[2], 6), round(r[3], 6)) for r in rows] == [(round(r[2], 6), round(r[3], 6)) for r in flown]


def test_a_ground_station_address_that_is_not_ipv4_is_refused_before_anything_starts():
    r = subprocess.run([sys.executable, os.path.join(ROOT, "hil", "run_flight.py"), "--gcs-host", "lab-laptop",
                        "--folder", os.path.join(tempfile.mkdtemp(prefix="hil_gcs_bad_"), "flight")],
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 2
    assert "--gcs-host must be an IPv4 address" in r.stderr
