"""What the rviz view shows, ROS-free: the aircraft's pose, its track coloured by who flew it,
the mission, the ceiling and the current decision. Positions come in NED feet from home (the
aircraft's units) and leave in the map frame of REP 103: ENU metres, body axes FLU."""
import math
from dataclasses import dataclass, field
from typing import List, Tuple

from stack_common.units import M_PER_FT

from . import definitions
from .figures import CONTROLLER_COLOURS, CONTROLLER_LABELS


def hex_rgb(colour):
    return tuple(int(colour[i:i + 2], 16) / 255.0 for i in (1, 3, 5))


def enu_m(north_ft, east_ft, height_ft):
    return (east_ft * M_PER_FT, north_ft * M_PER_FT, height_ft * M_PER_FT)


def quaternion_flu_in_enu(roll_deg, pitch_deg, heading_deg):
    """(x, y, z, w) of the body's FLU axes in ENU, from the aircraft's NED 3-2-1 Euler angles."""
    phi, theta, psi = (math.radians(a) for a in (roll_deg, pitch_deg, heading_deg))
    cf, sf, ct, st, cp, sp = math.cos(phi), math.sin(phi), math.cos(theta), math.sin(theta), math.cos(psi), math.sin(psi)
    # Body FRD in NED (3-2-1).
    r = [[ct * cp, sf * st * cp - cf * sp, cf * st * cp + sf * sp],
         [ct * sp, sf * st * sp + cf * cp, cf * st * sp - sf * cp],
         [-st, sf * ct, cf * ct]]
    # ENU rows are NED's (E, N, -D); FLU columns are FRD's (F, -R, -D).
    ned_to_enu = [r[1], r[0], [-v for v in r[2]]]
    m = [[row[0], -row[1], -row[2]] for row in ned_to_enu]
    trace = m[0][0] + m[1][1] + m[2][2]
    if trace > 0.0:
        s = 2.0 * math.sqrt(trace + 1.0)
        return ((m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s, 0.25 * s)
    i = max(range(3), key=lambda k: m[k][k])
    j, k = (i + 1) % 3, (i + 2) % 3
    s = 2.0 * math.sqrt(1.0 + m[i][i] - m[j][j] - m[k][k])
    q = [0.0, 0.0, 0.0]
    q[i] = 0.25 * s
    q[j] = (m[j][i] + m[i][j]) / s
    q[k] = (m[k][i] + m[i][k]) / s
    return (q[0], q[1], q[2], (m[k][j] - m[j][k]) / s)


@dataclass
class View:
    """The state of the rviz view; feed it messages' values, read its markers."""
    ceiling_ft: float
    controller_names: dict  # value -> name, from DecisionStatus's definition
    reason_names: dict      # bit -> name
    min_step_ft: float = 10.0   # a track point per this much travel (an hour stays light in rviz)
    max_points: int = 20000
    track: List[Tuple[Tuple[float, float, float], str]] = field(default_factory=list)
    waypoints: List[Tuple[float, float, float]] = field(default_factory=list)
    controller: str = ""
    reasons: List[str] = field(default_factory=list)
    pose: Tuple = None  # (enu position m, quaternion)

    def on_decision(self, controller, reasons):
        self.controller = self.controller_names.get(int(controller), "controller %d" % int(controller))
        self.reasons = definitions.bit_names(int(reasons), self.reason_names)

    def on_plan(self, waypoints_ned_ft):
        self.waypoints = list(waypoints_ned_ft)

    def on_state(self, north_ft, east_ft, height_ft, roll_deg, pitch_deg, heading_deg):
        here = enu_m(north_ft, east_ft, height_ft)
        self.pose = (here, quaternion_flu_in_enu(roll_deg, pitch_deg, heading_deg))
        who = self.controller or "unknown"
        # The strip always ends where the aircraft is; points before it lie min_step_ft apart.
        if (len(self.track) >= 2 and self.track[-1][1] == who and self.track[-2][1] == who
                and math.dist(self.track[-2][0], here) < self.min_step_ft * M_PER_FT):
            self.track[-1] = (here, who)
            return
        self.track.append((here, who))
        if len(self.track) > self.max_points:
            del self.track[: len(self.track) - self.max_points]

    def text(self):
        if not self.controller:
            return "no decision yet"
        label = CONTROLLER_LABELS.get(self.controller, self.controller)
        return "%s: %s" % (label, ", ".join(self.reasons)) if self.reasons else label

    def ceiling_plane(self):
        """(centre, (size_x, size_y)) in metres covering the mission and the track, with margin."""
        xs = [p[0] for p, _ in self.track] + [enu_m(*w)[0] for w in self.waypoints] + [0.0]
        ys = [p[1] for p, _ in self.track] + [enu_m(*w)[1] for w in self.waypoints] + [0.0]
        margin_m = 150.0
        cx, cy = (min(xs) + max(xs)) / 2.0, (min(ys) + max(ys)) / 2.0
        return ((cx, cy, self.ceiling_ft * M_PER_FT),
                (max(xs) - min(xs) + 2 * margin_m, max(ys) - min(ys) + 2 * margin_m))

    def track_colours(self):
        return [hex_rgb(CONTROLLER_COLOURS.get(who, "#7f7f7f")) for _, who in self.track]
