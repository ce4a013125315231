"""A flight's data as CSV files in SI units, for pandas, PlotJuggler and spreadsheets: one file
per stream, one row per message, every column named with its unit.

The bags hold the thesis's messages in feet, ft/s and g; here lengths are metres, speeds m/s,
accelerations m/s^2, through report_core's one set of conversions (flight_log.py). Angles keep
the unit the message has, named in the column (_rad or _deg). Every file starts with the two
times: t_s, seconds from the flight's first message (the report's time axis), and ros_time_s,
the message's own stamp in ROS time (simulation time in a lockstep HiL flight)."""
import csv
import os

from stack_common.units import G_MPS2, M_PER_FT

from . import definitions
from .flight_log import TOPIC_DATA, TOPIC_DECISION, TOPIC_SERVO_OP, TOPIC_TRUTH, ReportError

_FT_S2_TO_MPS2 = M_PER_FT  # ft/s^2 -> m/s^2, the same foot
_COUNT = "count"  # an integer field (a flag, an id, a bit set): written without a decimal point

# Per file: the topic, then (column, the LogBuilder's field, scale or _COUNT).
STREAMS = (
    ("ins", TOPIC_DATA, (  # what the VN-200 measured, as the controller relayed it on /data
        ("lat_deg", "lat_deg", 1.0), ("lon_deg", "lon_deg", 1.0), ("alt_m", "alt_m", 1.0),
        ("roll_rad", "roll_rad", 1.0), ("pitch_rad", "pitch_rad", 1.0), ("yaw_rad", "yaw_rad", 1.0),
        ("p_rad_s", "p_rad_s", 1.0), ("q_rad_s", "q_rad_s", 1.0), ("r_rad_s", "r_rad_s", 1.0),
        ("v_north_mps", "vn_mps", 1.0), ("v_east_mps", "ve_mps", 1.0), ("v_down_mps", "vd_mps", 1.0),
        ("accel_x_mps2", "ax_g", G_MPS2), ("accel_y_mps2", "ay_g", G_MPS2),
        ("accel_z_mps2", "az_g", G_MPS2),
        ("airspeed_mps", "air_velocity_ftps", M_PER_FT),
        ("ha_link_up", "a_usbstatus", _COUNT), ("ins_link_up", "v_usbstatus", _COUNT))),
    ("truth", TOPIC_TRUTH, (  # HiL only: the simulator's state
        ("lat_deg", "latitude_deg", 1.0), ("lon_deg", "longitude_deg", 1.0),
        ("alt_msl_m", "altitude_msl_m", 1.0), ("height_above_home_m", "height_above_home_ft", M_PER_FT),
        ("north_m", "north_ft", M_PER_FT), ("east_m", "east_ft", M_PER_FT),
        ("roll_deg", "roll_deg", 1.0), ("pitch_deg", "pitch_deg", 1.0), ("heading_deg", "heading_deg", 1.0),
        ("p_deg_s", "p_deg_s", 1.0), ("q_deg_s", "q_deg_s", 1.0), ("r_deg_s", "r_deg_s", 1.0),
        ("accel_x_mps2", "accel_x_ft_s2", _FT_S2_TO_MPS2), ("accel_y_mps2", "accel_y_ft_s2", _FT_S2_TO_MPS2),
        ("accel_z_mps2", "accel_z_ft_s2", _FT_S2_TO_MPS2),
        ("airspeed_mps", "airspeed_ftps", M_PER_FT), ("groundspeed_mps", "groundspeed_ftps", M_PER_FT),
        ("alpha_deg", "alpha_deg", 1.0), ("beta_deg", "beta_deg", 1.0),
        ("elevator_deg", "elevator_deg", 1.0), ("aileron_deg", "aileron_deg", 1.0),
        ("rudder_deg", "rudder_deg", 1.0), ("throttle", "throttle", 1.0),
        ("ha_elevator_deg", "ha_elevator_deg", 1.0), ("ha_aileron_deg", "ha_aileron_deg", 1.0),
        ("ha_rudder_deg", "ha_rudder_deg", 1.0), ("ha_throttle", "ha_throttle", 1.0),
        ("controller", "controller", _COUNT), ("on_ground", "on_ground", _COUNT))),
    ("servo_commands", TOPIC_SERVO_OP, (  # the HP's commands to the HA
        ("seq", "seq", _COUNT), ("throttle", "throttle", 1.0), ("elevator_deg", "elevator_deg", 1.0),
        ("aileron_deg", "aileron_deg", 1.0), ("rudder_deg", "rudder_deg", 1.0),
        ("alpha_est_deg", "alpha_est_deg", 1.0), ("beta_est_deg", "beta_est_deg", 1.0),
        ("estimator_converged", "estimator_converged", _COUNT),
        ("sensor_links_healthy", "sensor_links_healthy", _COUNT))),
    ("decision", TOPIC_DECISION, (  # the HA's decision each period and what it sent the servos
        ("controller", "controller", _COUNT), ("reasons", "reasons", _COUNT),
        ("reasons_at_switch", "reasons_at_switch", _COUNT), ("restart_count", "restart_count", _COUNT),
        ("restart_requested", "restart_requested", _COUNT), ("last_seq", "last_seq", _COUNT),
        ("stable_for_s", "stable_for_s", 1.0), ("airspeed_mps", "airspeed_ftps", M_PER_FT),
        ("altitude_agl_m", "altitude_agl_ft", M_PER_FT),
        ("state_region_max", "state_region_max", 1.0), ("actuator_region_max", "actuator_region_max", 1.0),
        ("throttle", "throttle", 1.0), ("elevator_deg", "elevator_deg", 1.0),
        ("aileron_deg", "aileron_deg", 1.0), ("rudder_deg", "rudder_deg", 1.0))),
)


def export_csv(builder, definition_texts, out_dir):
    """Writes <out_dir>/<stream>.csv for each stream the log holds; returns their paths. The
    decision file also names its controller and reasons (text columns), by the bag's own
    DecisionStatus definition."""
    present = [(name, topic, columns) for name, topic, columns in STREAMS if builder.table(topic) is not None]
    if not present:
        raise ReportError("none of %s in this bag: nothing to export"
                          % ", ".join(topic for _, topic, _ in STREAMS))
    text = definition_texts.get(TOPIC_DECISION, "")
    controller_names = definitions.constants(text, "CONTROLLER_")
    reason_names = definitions.constants(text, "REASON_")
    os.makedirs(out_dir, exist_ok=True)
    paths = []
    for name, topic, columns in present:
        table = builder.table(topic)
        path = os.path.join(out_dir, name + ".csv")
        header = ["t_s", "ros_time_s"] + [column for column, _, _ in columns]
        sources = [(table.columns[field], scale) for _, field, scale in columns]
        decision = topic == TOPIC_DECISION
        if decision:
            header += ["controller_name", "reason_names"]
        with open(path, "w", newline="") as f:
            out = csv.writer(f, lineterminator="\n")
            out.writerow(header)
            for i in range(len(table)):
                t_s = float(table.t[i])
                row = [t_s, t_s + builder.t_min]
                for values, scale in sources:
                    value = float(values[i])
                    row.append(int(value) if scale == _COUNT and value == value else
                               value if scale == _COUNT else value * scale)
                if decision:
                    row.append(controller_names.get(int(table.controller[i]), ""))
                    row.append("|".join(definitions.bit_names(table.reasons[i], reason_names)))
                out.writerow(row)
        paths.append(path)
    return paths
