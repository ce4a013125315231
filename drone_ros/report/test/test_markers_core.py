"""The rviz view's core: frames (NED feet in, ENU metres and FLU body out), the track's spacing
and colours, the decision text."""
import math
import os

import pytest


from report_core import markers  # noqa: E402

NAMES = {0: "HP", 1: "HA", 2: "RECOVERING"}
REASONS = {1: "NO_COMMAND", 128: "CEILING"}


def rotate(q, v):
    x, y, z, w = q
    m = [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
         [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
         [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]
    return [sum(m[i][j] * v[j] for j in range(3)) for i in range(3)]


@pytest.mark.parametrize("roll, pitch, heading, forward_enu, left_enu", [
    (0.0, 0.0, 0.0, (0, 1, 0), (-1, 0, 0)),      # heading north: nose to +y, left wing to -x (west)
    (0.0, 0.0, 90.0, (1, 0, 0), (0, 1, 0)),      # heading east
    (0.0, 30.0, 0.0, (0, math.cos(math.radians(30)), math.sin(math.radians(30))), (-1, 0, 0)),  # nose up
    (30.0, 0.0, 0.0, (0, 1, 0), (-math.cos(math.radians(30)), 0, math.sin(math.radians(30)))),  # right wing down
    (10.0, -20.0, 200.0, None, None),            # any attitude: a unit quaternion
])
def test_body_axes_land_where_rep_103_puts_them(roll, pitch, heading, forward_enu, left_enu):
    q = markers.quaternion_flu_in_enu(roll, pitch, heading)
    assert sum(c * c for c in q) == pytest.approx(1.0)
    if forward_enu is not None:
        assert rotate(q, (1, 0, 0)) == pytest.approx(forward_enu, abs=1e-9)
        assert rotate(q, (0, 1, 0)) == pytest.approx(left_enu, abs=1e-9)


def test_track_keeps_a_point_per_step_ends_at_the_aircraft_and_colours_who_flew():
    view = markers.View(ceiling_ft=400.0, controller_names=NAMES, reason_names=REASONS, min_step_ft=10.0)
    view.on_decision(0, 0)
    for i in range(101):  # 100 ft east in 1 ft steps
        view.on_state(0.0, float(i), 300.0, 0.0, 0.0, 90.0)
    assert 10 <= len(view.track) <= 12
    assert view.track[-1][0] == pytest.approx(markers.enu_m(0.0, 100.0, 300.0))
    view.on_decision(1, 1)
    view.on_state(0.0, 100.5, 300.0, 0.0, 0.0, 90.0)  # the switch starts a new stretch at once
    assert view.track[-1][1] == "HA"
    colours = view.track_colours()
    assert colours[0] == markers.hex_rgb("#1f77b4") and colours[-1] == markers.hex_rgb("#d62728")
    assert view.text() == "HA: NO_COMMAND"


def test_the_ceiling_plane_covers_the_mission_and_the_track_at_the_ceiling():
    view = markers.View(ceiling_ft=400.0, controller_names=NAMES, reason_names=REASONS)
    view.on_plan([(2000.0, -1000.0, 300.0)])
    view.on_state(-500.0, 3000.0, 300.0, 0.0, 0.0, 0.0)
    (cx, cy, cz), (sx, sy) = view.ceiling_plane()
    assert cz == pytest.approx(400.0 * 0.3048)
    assert cx - sx / 2 < -1000.0 * 0.3048 and cx + sx / 2 > 3000.0 * 0.3048
    assert cy - sy / 2 < -500.0 * 0.3048 and cy + sy / 2 > 2000.0 * 0.3048


def test_text_before_any_decision_says_so():
    view = markers.View(ceiling_ft=400.0, controller_names=NAMES, reason_names=REASONS)
    assert view.text() == "no decision yet"
    view.on_decision(2, 0)
    assert view.text() == "recovering"


def test_saved_rviz_view_shows_the_markers_node_and_the_aircraft_pose():
    import yaml
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..")
    with open(os.path.join(root, "rviz", "flight.rviz")) as f:
        config = yaml.safe_load(f)["Visualization Manager"]
    assert config["Global Options"]["Fixed Frame"] == "map"
    displays = {d["Class"]: d for d in config["Displays"]}
    # Relative: rviz started by view.launch in an aircraft's namespace shows that aircraft's.
    assert displays["rviz/MarkerArray"]["Marker Topic"] == "flight_markers"
    assert set(displays["rviz/MarkerArray"]["Namespaces"]) == {"track", "waypoints", "ceiling", "decision"}
    assert displays["rviz/Axes"]["Reference Frame"] == "base_link"
    # REP-105, as the vn200 node broadcasts it.
    assert "vn200" in displays["rviz/TF"]["Tree"]["map"]["odom"]["base_link"]
