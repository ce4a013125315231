"""Builds the whole report of one flight into a folder: the PNGs and index.html."""
import json
import os

from . import figures, page, switches as switches_mod
from .flight_log import FlightLog, ReportError

FIGURES = (
    (figures.outputs, False, "Fig. 5.3: HP output, HA output and the applied output per surface"),
    (figures.accelerations, False, "Fig. 5.4: accelerations"),
    (figures.euler_angles, False, "Fig. 5.5: Euler angles"),
    (figures.body_rates, False, "Fig. 5.6: body rates"),
    (figures.velocity, False, "Fig. 5.7: velocity"),
    (figures.track, False, "Track over the mission, coloured by who flew each stretch"),
    (figures.altitude, True, "Altitude against the ceiling"),
    (figures.airspeed, True, "Airspeed against stall"),
    (figures.link_and_timing, True, "Link health and deadline timing"),
)


def make_report(builder, definition_texts, limits, out_dir, title):
    """builder: a LogBuilder fed the flight's records; definition_texts: {topic: message
    definition}; limits: the aircraft's limits.yaml. Returns the path of index.html."""
    log = FlightLog(builder, definition_texts)
    for section, key in (("state", "ceiling_agl_ft"), ("state", "stall_speed_ftps"),
                         ("state", "airborne_agl_ft"), ("decision", "rate_hz"),
                         ("decision", "no_command_timeout_s")):
        if key not in limits.get(section, {}):
            raise ReportError("limits.yaml has no %s.%s" % (section, key))
    os.makedirs(out_dir, exist_ok=True)
    runs = switches_mod.runs(log)
    switch_list = switches_mod.switches(log)
    made = []
    for draw, needs_limits, caption in FIGURES:
        args = (log, limits, runs, switch_list, out_dir) if needs_limits else (log, runs, switch_list, out_dir)
        made.append((draw(*args), caption))

    notes = []
    if log.truth is None:
        notes.append("No simulator truth (/hil/truth) in this log: the state figures show what the "
                     "sensors measured (VN-200 on /data, pitot on /pwm), and Fig. 5.3's applied "
                     "output is what the HA sent to the servos.")
    missing = [name for name, table in (("/servo_op", log.servo_op), ("/pwm", log.pwm),
                                        ("/ins", log.ins), ("/data", log.data)) if table is None]
    if missing:
        notes.append("Not in this log: %s." % ", ".join(missing))
    if not log.waypoints:
        notes.append("No flight plan (/way) in this log.")
    facts = [("aircraft", limits.get("aircraft", "?")),
             ("duration", "%.1f s" % log.duration_s),
             ("state from", "simulator truth" if log.truth is not None else "sensors (real flight)"),
             ("switches", len(switch_list)),
             ("HP restarts requested", int(log.decision.restart_count.max()))]
    index = os.path.join(out_dir, "index.html")
    with open(index, "w") as f:
        f.write(page.render(title, facts, runs, switch_list, made, notes))
    with open(os.path.join(out_dir, "switches.json"), "w") as f:
        json.dump([s.__dict__ for s in switch_list], f, indent=1)
    return index
