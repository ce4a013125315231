"""A flight as arrays: the decoded records of the topics a flight bag holds, turned into one
table per topic on a common time axis (seconds from the first message).

A record is a dict of the message's fields (nested messages as dicts, times as float
seconds) plus "_t_bag", the time the recorder received it. A message's own stamp is its time;
the receive time stands in only where a message has no stamp or an unset one.

A topic's messages keep the order they were sent in, and a stamp earlier than the one before it
is held at that one: the HA stamps on its clock as rosserial's time sync last set it, and a sync
can set it back by the host's lag (tens of ms in a loaded lockstep HiL). Sorted by stamp, the
periods on either side of such a step interleave, and one switch reads as a dozen."""
import math
from array import array

import numpy as np
from stack_common import geo
from stack_common.units import FT_PER_M

from . import definitions

TOPIC_TRUTH = "/hil/truth"
TOPIC_DECISION = "/decision_status"
TOPIC_SERVO_OP = "/servo_op"
TOPIC_PWM = "/pwm"
TOPIC_INS = "/ins"
TOPIC_DATA = "/data"
TOPIC_WAY = "/way"
TOPIC_HOME = "/home"  # the HA's latched home, the whole stack's one (drone_ros/HomePosition)
TOPICS = (TOPIC_TRUTH, TOPIC_DECISION, TOPIC_SERVO_OP, TOPIC_PWM, TOPIC_INS, TOPIC_DATA, TOPIC_WAY,
          TOPIC_HOME)


class ReportError(Exception):
    """A flight the report cannot be made from, with the reason a person can act on."""


class Table:
    """Columns of one topic: numpy arrays of equal length, "t" the time from the flight's start."""

    def __init__(self, columns):
        self.columns = columns

    def __getattr__(self, name):
        try:
            return self.__dict__["columns"][name]
        except KeyError:
            raise AttributeError(name) from None

    def __len__(self):
        return len(self.columns["t"])


def _field(record, path):
    value = record
    for part in path.split("."):
        if "[" in part:
            name, index = part[:-1].split("[")
            value = value[name][int(index)]
        else:
            value = value[part]
    return value


def _stamp(record, zero_is_a_time=False):
    """A zero stamp means "unset" in ROS, except on a simulator's clock, which starts at zero."""
    stamp = record.get("header", {}).get("stamp") if isinstance(record.get("header"), dict) else None
    if stamp is None:
        stamp = record.get("stamp")
    if isinstance(stamp, (int, float)) and (stamp > 0.0 or (zero_is_a_time and stamp == 0.0)):
        return float(stamp)
    return float(record["_t_bag"])


TRUTH_FIELDS = {name: name for name in (
    "latitude_deg", "longitude_deg", "altitude_msl_m", "height_above_home_ft", "north_ft", "east_ft",
    "roll_deg", "pitch_deg", "heading_deg", "p_deg_s", "q_deg_s", "r_deg_s",
    "accel_x_ft_s2", "accel_y_ft_s2", "accel_z_ft_s2", "airspeed_ftps", "groundspeed_ftps",
    "alpha_deg", "beta_deg", "elevator_deg", "aileron_deg", "rudder_deg", "throttle",
    "ha_elevator_deg", "ha_aileron_deg", "ha_rudder_deg", "ha_throttle", "controller", "on_ground")}
DECISION_FIELDS = {name: name for name in (
    "stamp", "controller", "reasons", "reasons_at_switch", "restart_count", "restart_requested",
    "last_seq", "stable_for_s", "airspeed_ftps", "altitude_agl_ft", "state_region_max",
    "actuator_region_max", "throttle", "elevator_deg", "aileron_deg", "rudder_deg")}
SERVO_OP_FIELDS = {name: name for name in (
    "seq", "stamp", "throttle", "elevator_deg", "aileron_deg", "rudder_deg", "alpha_est_deg",
    "beta_est_deg", "estimator_converged", "sensor_links_healthy")}
PWM_FIELDS = {"piccic": "PICCIC", "velocity_ftps": "velocity", "usbstatus": "usbstatus"}
INS_FIELDS = {"usbstatus": "usbstatus", "ins_status": "ins_status", "num_sats": "num_sats",
              "gps_fix": "gps_fix"}
DATA_FIELDS = {
    "roll_rad": "angle.x", "pitch_rad": "angle.y", "yaw_rad": "angle.z",
    "lat_deg": "lla.x", "lon_deg": "lla.y", "alt_m": "lla.z",
    "vn_mps": "velocity.x", "ve_mps": "velocity.y", "vd_mps": "velocity.z",
    "p_rad_s": "angrate.x", "q_rad_s": "angrate.y", "r_rad_s": "angrate.z",
    "ax_g": "acceleration.x", "ay_g": "acceleration.y", "az_g": "acceleration.z",
    "air_velocity_ftps": "air_velocity", "a_usbstatus": "a_usbstatus", "v_usbstatus": "v_usbstatus",
}


FIELD_TABLES = {TOPIC_TRUTH: TRUTH_FIELDS, TOPIC_DECISION: DECISION_FIELDS,
                TOPIC_SERVO_OP: SERVO_OP_FIELDS, TOPIC_PWM: PWM_FIELDS, TOPIC_INS: INS_FIELDS,
                TOPIC_DATA: DATA_FIELDS}
# The top-level fields read per topic, so an edge decoding a long log keeps only these.
FIELDS_BY_TOPIC = {
    topic: {"header", "stamp"} | {path.split(".")[0].split("[")[0] for path in fields.values()}
    for topic, fields in FIELD_TABLES.items()}
FIELDS_BY_TOPIC[TOPIC_WAY] = {"north", "east", "height", "fp"}
FIELDS_BY_TOPIC[TOPIC_HOME] = {"latitude", "longitude", "altitude"}


class LogBuilder:
    """Takes records one at a time and keeps only the columns the report draws (8 bytes a value),
    so an hour of flight fits in memory."""

    def __init__(self, sim_time=False):
        self.sim_time = sim_time  # a HiL log: every stamp is on the simulator's clock
        self.columns = {topic: {name: array("d") for name in ("t", *fields)}
                        for topic, fields in FIELD_TABLES.items()}
        self.last_plan = None
        self.home = None  # (lat_deg, lon_deg, alt_m): the last /home, latched, so in every log
        self.t_min = math.inf
        self.t_max = -math.inf

    def add(self, topic, record):
        if topic == TOPIC_WAY:  # a plan, not a time series: it has no stamp and spans no time
            if _flight_plan(record):
                self.last_plan = record
            return
        if topic == TOPIC_HOME:  # likewise a fact, not a series
            try:
                self.home = (float(record["latitude"]), float(record["longitude"]), float(record["altitude"]))
            except (KeyError, TypeError, ValueError):
                raise ReportError("%s has no latitude/longitude/altitude: the bag was recorded with "
                                  "another version of the message" % TOPIC_HOME) from None
            return
        t = _stamp(record, self.sim_time)
        if topic in FIELD_TABLES:
            columns = self.columns[topic]
            values = []
            for name, path in FIELD_TABLES[topic].items():
                try:
                    values.append(float(_field(record, path)))
                except (KeyError, IndexError, TypeError, ValueError) as error:
                    raise ReportError("%s has no field %s (%s): the bag was recorded with another "
                                      "version of the message" % (topic, path, error)) from None
            columns["t"].append(t)
            for name, value in zip(FIELD_TABLES[topic], values):
                columns[name].append(value)
        else:
            return
        self.t_min, self.t_max = min(self.t_min, t), max(self.t_max, t)

    def table(self, topic):
        columns = self.columns[topic]
        if not columns["t"]:
            return None
        t = np.maximum.accumulate(np.frombuffer(columns["t"], dtype=float)) - self.t_min
        out = {"t": t}
        for name in FIELD_TABLES[topic]:
            out[name] = np.frombuffer(columns[name], dtype=float)
        return Table(out)


class FlightLog:
    """Everything the report draws, decoded; None for a topic the bag does not hold."""

    def __init__(self, builder, definition_texts):
        if not builder.columns[TOPIC_DECISION]["t"]:
            raise ReportError("no %s messages: the report is built around the HA's decisions, "
                              "record that topic" % TOPIC_DECISION)
        self.t0 = builder.t_min
        self.duration_s = builder.t_max - builder.t_min
        self.truth = builder.table(TOPIC_TRUTH)
        self.decision = builder.table(TOPIC_DECISION)
        self.servo_op = builder.table(TOPIC_SERVO_OP)
        self.pwm = builder.table(TOPIC_PWM)
        self.ins = builder.table(TOPIC_INS)
        self.data = builder.table(TOPIC_DATA)
        self.waypoints = _flight_plan(builder.last_plan) if builder.last_plan else []
        self.home = builder.home
        text = definition_texts.get(TOPIC_DECISION, "")
        self.controller_names = definitions.constants(text, "CONTROLLER_")
        self.reason_names = definitions.constants(text, "REASON_")
        if not self.controller_names or not self.reason_names:
            raise ReportError("the definition of %s names no CONTROLLER_* or REASON_* constants"
                              % TOPIC_DECISION)
        self.controller_value = {name: value for value, name in self.controller_names.items()}

    def controller_at(self, t):
        """The controller in force at each time in t (the HA's decision held until the next)."""
        index = np.searchsorted(self.decision.t, t, side="right") - 1
        return self.decision.controller[np.clip(index, 0, None)].astype(int)

    def position(self):
        """(t, north_ft, east_ft, height_ft, source): the track, from truth when simulated, else
        from the INS fixes relayed on /data around the HA's /home (or, in a log without it, the
        first fix)."""
        if self.truth is not None:
            return (self.truth.t, self.truth.north_ft, self.truth.east_ft,
                    self.truth.height_above_home_ft, "simulator truth (/hil/truth)")
        if self.data is None:
            return None
        fixed = (self.data.lat_deg != 0.0) | (self.data.lon_deg != 0.0)
        if not fixed.any():
            return None
        t = self.data.t[fixed]
        lat, lon, alt = self.data.lat_deg[fixed], self.data.lon_deg[fixed], self.data.alt_m[fixed]
        if self.home is not None:
            home_lat, home_lon, home_alt = self.home
            source = "measured (VN-200 fixes on /data, home = the HA's /home)"
        else:
            home_lat, home_lon, home_alt = lat[0], lon[0], alt[0]
            source = "measured (VN-200 fixes on /data, home = first fix in the log: no /home recorded)"
        try:
            north, east = ned_from_home(lat, lon, home_lat, home_lon)
        except ValueError:  # a first fix geo_ref_init refuses: no home to place the fixes around
            return None
        return (t, north, east, (alt - home_alt) * FT_PER_M, source)


def ned_from_home(lat_deg, lon_deg, home_lat_deg, home_lon_deg):
    """North and east of home [ft] of arrays of fixes: the stack's one flat-earth conversion
    (geo_wgs84.c, through stack_common.geo), the short way round across the antimeridian."""
    return geo.ref(float(home_lat_deg), float(home_lon_deg)).north_east_ft_arrays(lat_deg, lon_deg)


def _flight_plan(record):
    """A /way record's plan as [(north_ft, east_ft, height_ft)], [] when it holds none."""
    count = int(record.get("fp", 0))
    if 0 < count <= len(record.get("north", ())):
        return [(float(record["north"][i]), float(record["east"][i]), float(record["height"][i]))
                for i in range(count)]
    return []
