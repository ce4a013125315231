"""The report's figures, one PNG each. Every time plot shades the stretches the HP was not
flying, in the colour of who was, and marks each switch with a vertical line."""
import os

import matplotlib

matplotlib.use("Agg")  # files only: no display on a flight computer or in CI
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402

from stack_common.units import FT_PER_M, G_FTPS2  # noqa: E402

# Who flew, by the DecisionStatus constant's name (without CONTROLLER_).
CONTROLLER_COLOURS = {"HP": "#1f77b4", "HA": "#d62728", "RECOVERING": "#ff7f0e",
                      "HA_LATCHED": "#9467bd", "MANUAL": "#2ca02c"}
CONTROLLER_LABELS = {"HP": "HP", "HA": "HA", "RECOVERING": "recovering", "HA_LATCHED": "HA latched",
                     "MANUAL": "pilot"}
_OTHER = "#7f7f7f"
DPI = 110


def colour(controller):
    return CONTROLLER_COLOURS.get(controller, _OTHER)


def label(controller):
    return CONTROLLER_LABELS.get(controller, controller)


def _shade(axes, runs, switches):
    for ax in axes:
        for run in runs:
            if run.controller != "HP":
                ax.axvspan(run.start_s, run.end_s, color=colour(run.controller), alpha=0.15, lw=0)
        for s in switches:
            ax.axvline(s.t_s, color=colour(s.to_controller), lw=0.8, ls="--")


def _shading_legend(runs):
    seen = []
    for run in runs:
        if run.controller != "HP" and run.controller not in seen:
            seen.append(run.controller)
    return [Patch(color=colour(c), alpha=0.3, label="%s flying" % label(c)) for c in seen]


def _broken(t, y, gap_periods=5.0):
    """t, y with a NaN wherever samples stop for longer than gap_periods typical periods, so a
    line is not drawn across a stretch with no messages (a crashed HP)."""
    t, y = np.asarray(t, dtype=float), np.asarray(y, dtype=float)
    if len(t) < 3:
        return t, y
    dt = np.diff(t)
    gaps = np.flatnonzero(dt > gap_periods * max(np.median(dt), 1e-6)) + 1
    return np.insert(t, gaps, np.nan), np.insert(y, gaps, np.nan)


MAX_POINTS = 8000  # per line: several per pixel of a 1200-pixel-wide plot


def _thin(t, y, max_points=MAX_POINTS):
    """At most max_points samples: the min and the max of each of max_points/2 runs of samples,
    in time order. The line looks the same at the figure's resolution, no spike is lost, and an
    hour at 100 Hz draws in seconds."""
    t, y = np.asarray(t, dtype=float), np.asarray(y, dtype=float)
    bins = max_points // 2
    if len(t) <= max_points or bins < 1:
        return t, y
    k = len(t) // bins
    n = bins * k
    rows = y[:n].reshape(bins, k)
    low = np.argmin(np.where(np.isnan(rows), np.inf, rows), axis=1)
    high = np.argmax(np.where(np.isnan(rows), -np.inf, rows), axis=1)
    base = np.arange(bins) * k
    keep = np.sort(np.concatenate((base + low, base + high, np.arange(n, len(t)))))
    keep = np.unique(keep)
    return t[keep], y[keep]


def _line(ax, t, y, *args, **kwargs):
    """A time series drawn thinned, and broken where messages stopped."""
    return ax.plot(*_broken(*_thin(t, y)), *args, **kwargs)


def _legend_above(ax, handles):
    ax.legend(handles=handles, loc="lower left", bbox_to_anchor=(0.0, 1.02), ncol=4, fontsize=8,
              frameon=False)


def _save(fig, out_dir, name):
    path = os.path.join(out_dir, name)
    fig.savefig(path, dpi=DPI)
    plt.close(fig)
    return name


def _no_data(ax, what):
    ax.text(0.5, 0.5, "no %s in this log" % what, transform=ax.transAxes, ha="center", va="center",
            color="0.4")


def _time_figure(title, rows, runs, switches, source):
    fig, axes = plt.subplots(rows, 1, figsize=(11, max(2.2 * rows + 1.0, 4.5)), sharex=True, squeeze=False)
    axes = axes[:, 0]
    fig.suptitle(title)
    if source:
        fig.text(0.01, 0.005, "source: " + source, fontsize=8, color="0.3")
    _shade(axes, runs, switches)
    axes[-1].set_xlabel("time [s]")
    for ax in axes:
        ax.grid(True, alpha=0.3)
    return fig, axes


def outputs(log, runs, switches, out_dir):
    """Thesis Fig. 5.3: the HP's command, the HA safety controller's command and what was
    applied, one panel per surface."""
    surfaces = (("elevator_deg", "ha_elevator_deg", "elevator [deg]"),
                ("aileron_deg", "ha_aileron_deg", "aileron [deg]"),
                ("rudder_deg", "ha_rudder_deg", "rudder [deg]"),
                ("throttle", "ha_throttle", "throttle [0..1]"))
    if log.truth is not None:
        source = ("HP: /servo_op; HA: the safety controller's command every period and applied: at "
                  "the surfaces after the servo model (both /hil/truth)")
    else:
        source = ("HP: /servo_op; applied: what the HA sent to the servos (/decision_status); HA: "
                  "its command is logged only while it drives, so it equals applied there")
    fig, axes = _time_figure("Outputs of the performance (HP) and safety (HA) controllers and what "
                             "was applied", len(surfaces), runs, switches, source)
    d = log.decision
    ha_values = [log.controller_value[n] for n in ("HA", "RECOVERING", "HA_LATCHED")
                 if n in log.controller_value]
    ha_driving = np.isin(d.controller, ha_values)
    for ax, (field, ha_field, ylabel) in zip(axes, surfaces):
        if log.servo_op is not None:
            _line(ax, log.servo_op.t, getattr(log.servo_op, field), lw=0.9,
                    color=colour("HP"), label="HP output")
        if log.truth is not None:
            _line(ax, log.truth.t, getattr(log.truth, ha_field), lw=0.9, color=colour("HA"),
                    label="HA output")
            _line(ax, log.truth.t, getattr(log.truth, field), lw=1.2, color="k", ls=":",
                    label="applied (at the surface)")
        else:
            ha = np.where(ha_driving, getattr(d, field), np.nan)
            _line(ax, d.t, ha, lw=0.9, color=colour("HA"), label="HA output (while driving)")
            _line(ax, d.t, getattr(d, field), lw=1.2, color="k", ls=":", label="applied (HA to servos)")
        ax.set_ylabel(ylabel)
    _legend_above(axes[0], axes[0].get_legend_handles_labels()[0] + _shading_legend(runs))
    return _save(fig, out_dir, "fig5_3_outputs.png")


def _state_source(log):
    if log.truth is not None:
        return "simulator truth (/hil/truth)"
    return "measured: no /hil/truth in this log, so VN-200 values relayed by the controller on /data"


def _state_figure(log, runs, switches, out_dir, title, name, panels):
    """panels: (ylabel, truth field or None, function of log.data or None)."""
    fig, axes = _time_figure(title, len(panels), runs, switches, _state_source(log))
    for ax, (ylabel, truth_of, data_of) in zip(axes, panels):
        ax.set_ylabel(ylabel)
        if log.truth is not None and truth_of is not None:
            _line(ax, log.truth.t, truth_of(log.truth), lw=0.9)
        elif log.data is not None and data_of is not None:
            _line(ax, log.data.t, data_of(log.data), lw=0.9)
        else:
            _no_data(ax, ylabel)
    if _shading_legend(runs):
        _legend_above(axes[0], _shading_legend(runs))
    return _save(fig, out_dir, name)


def accelerations(log, runs, switches, out_dir):
    """Thesis Fig. 5.4, in g."""
    return _state_figure(log, runs, switches, out_dir, "Accelerations (specific force, body axes)",
                         "fig5_4_accelerations.png", [
                             ("a_x [g]", lambda t: t.accel_x_ft_s2 / G_FTPS2, lambda d: d.ax_g),
                             ("a_y [g]", lambda t: t.accel_y_ft_s2 / G_FTPS2, lambda d: d.ay_g),
                             ("a_z [g]", lambda t: t.accel_z_ft_s2 / G_FTPS2, lambda d: d.az_g)])


def euler_angles(log, runs, switches, out_dir):
    """Thesis Fig. 5.5, in degrees."""
    return _state_figure(log, runs, switches, out_dir, "Euler angles", "fig5_5_euler_angles.png", [
        ("roll [deg]", lambda t: t.roll_deg, lambda d: np.degrees(d.roll_rad)),
        ("pitch [deg]", lambda t: t.pitch_deg, lambda d: np.degrees(d.pitch_rad)),
        ("heading [deg]", lambda t: t.heading_deg, lambda d: np.degrees(d.yaw_rad) % 360.0)])


def body_rates(log, runs, switches, out_dir):
    """Thesis Fig. 5.6, in deg/s."""
    return _state_figure(log, runs, switches, out_dir, "Body rates", "fig5_6_body_rates.png", [
        ("P [deg/s]", lambda t: t.p_deg_s, lambda d: np.degrees(d.p_rad_s)),
        ("Q [deg/s]", lambda t: t.q_deg_s, lambda d: np.degrees(d.q_rad_s)),
        ("R [deg/s]", lambda t: t.r_deg_s, lambda d: np.degrees(d.r_rad_s))])


def velocity(log, runs, switches, out_dir):
    """Thesis Fig. 5.7, in ft/s."""
    return _state_figure(log, runs, switches, out_dir, "Velocity", "fig5_7_velocity.png", [
        ("true airspeed [ft/s]", lambda t: t.airspeed_ftps, lambda d: d.air_velocity_ftps),
        ("ground speed [ft/s]", lambda t: t.groundspeed_ftps,
         lambda d: np.hypot(d.vn_mps, d.ve_mps) * FT_PER_M)])


def track(log, runs, switches, out_dir):
    """North/east from home with the mission's waypoints, each stretch coloured by who flew it."""
    fig, ax = plt.subplots(figsize=(8.5, 8.5))
    position = log.position()
    if position is None:
        _no_data(ax, "position")
        source = ""
    else:
        t, north, east, _, source = position
        stride = max(1, len(t) // 20000)  # a track point every few feet is plenty on a map
        keep = np.unique(np.concatenate((np.arange(0, len(t), stride), [len(t) - 1])))
        t, north, east = t[keep], north[keep], east[keep]
        who = log.controller_at(t)
        points = np.column_stack((east, north)).reshape(-1, 1, 2)
        segments = np.concatenate((points[:-1], points[1:]), axis=1)
        names = [log.controller_names.get(int(v), str(int(v))) for v in who[:-1]]
        ax.add_collection(LineCollection(segments, colors=[colour(n) for n in names], linewidths=1.6))
        ax.plot(east[:1], north[:1], "k^", ms=9, label="start")
        ax.autoscale()
    if log.waypoints:
        wn = [w[0] for w in log.waypoints]
        we = [w[1] for w in log.waypoints]
        ax.plot(we + we[:1], wn + wn[:1], "o--", color="0.45", ms=4, lw=0.7, label="mission (/way)")
        for i, (n, e, _) in enumerate(log.waypoints):
            ax.annotate(str(i + 1), (e, n), fontsize=7, xytext=(3, 3), textcoords="offset points")
    flown = []
    for run in runs:
        if run.controller not in flown:
            flown.append(run.controller)
    handles = [Patch(color=colour(c), label="%s flying" % label(c)) for c in flown]
    ax.legend(handles=ax.get_legend_handles_labels()[0] + handles, loc="best", fontsize=8)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("east of home [ft]")
    ax.set_ylabel("north of home [ft]")
    ax.set_title("Track and mission")
    ax.grid(True, alpha=0.3)
    if source:
        fig.text(0.01, 0.005, "source: " + source, fontsize=8, color="0.3")
    return _save(fig, out_dir, "track.png")


def altitude(log, limits, runs, switches, out_dir):
    ceiling_ft = limits["state"]["ceiling_agl_ft"]
    airborne_ft = limits["state"]["airborne_agl_ft"]
    position = log.position()
    source = position[4] if position else ""
    fig, axes = _time_figure("Altitude against the ceiling", 1, runs, switches,
                             (source + "; " if source else "") + "HA-checked: /decision_status")
    ax = axes[0]
    if position is not None:
        _line(ax, position[0], position[3], lw=1.0, label="height above home")
    _line(ax, log.decision.t, log.decision.altitude_agl_ft, lw=0.8, ls="--", color="0.35",
            label="altitude the HA checked")
    ax.axhline(ceiling_ft, color="r", lw=1.2, label="ceiling %g ft" % ceiling_ft)
    ax.axhline(airborne_ft, color="0.5", lw=0.8, ls=":", label="airborne above %g ft" % airborne_ft)
    ax.set_ylabel("height [ft]")
    _legend_above(ax, ax.get_legend_handles_labels()[0] + _shading_legend(runs))
    return _save(fig, out_dir, "altitude.png")


def airspeed(log, limits, runs, switches, out_dir):
    stall_ftps = limits["state"]["stall_speed_ftps"]
    source = _state_source(log) + "; HA-checked: /decision_status; pitot: /pwm"
    fig, axes = _time_figure("Airspeed against stall", 1, runs, switches, source)
    ax = axes[0]
    if log.truth is not None:
        _line(ax, log.truth.t, log.truth.airspeed_ftps, lw=1.0, label="true airspeed")
    elif log.data is not None:
        _line(ax, log.data.t, log.data.air_velocity_ftps, lw=1.0, label="airspeed (/data)")
    _line(ax, log.decision.t, log.decision.airspeed_ftps, lw=0.8, ls="--", color="0.35",
            label="airspeed the HA checked")
    if log.pwm is not None and log.truth is None:
        _line(ax, log.pwm.t, log.pwm.velocity_ftps, lw=0.6, color="0.6", label="HA pitot (/pwm)")
    ax.axhline(stall_ftps, color="r", lw=1.2, label="stall %g ft/s" % stall_ftps)
    ax.set_ylabel("airspeed [ft/s]")
    _legend_above(ax, ax.get_legend_handles_labels()[0] + _shading_legend(runs))
    return _save(fig, out_dir, "airspeed.png")


# The reasons that speak of the link and of timing, by DecisionStatus constant name.
_TIMING_REASONS = ("NO_COMMAND", "DEADLINE_MISS", "FROZEN", "INTEGRITY", "SENSOR_LINK")


def link_and_timing(log, limits, runs, switches, out_dir):
    """Link health (serial links up, the timing and link checks the HA ran) and deadline timing
    (the age of the HP command the HA judged, the HP's command period)."""
    fig, axes = _time_figure("Link health and deadline timing", 3, runs, switches,
                             "/pwm, /ins, /servo_op, /decision_status")
    ax_links, ax_reasons, ax_age = axes
    if log.pwm is not None:
        ax_links.step(*_thin(log.pwm.t, log.pwm.usbstatus + 0.04), where="post", lw=1.0,
                      label="HP-HA link (/pwm usbstatus)")
    if log.ins is not None:
        ax_links.step(*_thin(log.ins.t, log.ins.usbstatus - 0.04), where="post", lw=1.0,
                      label="HP-VN-200 link (/ins usbstatus)")
    if log.servo_op is not None:
        ax_links.step(*_thin(log.servo_op.t, log.servo_op.sensor_links_healthy), where="post", lw=0.8,
                      ls="--", label="HP: sensor links healthy (/servo_op)")
    ax_links.set_ylim(-0.2, 1.3)
    ax_links.set_yticks([0, 1], ["down", "up"])
    ax_links.legend(loc="lower right", fontsize=8)

    names_by_bit = {bit: name for bit, name in log.reason_names.items() if name in _TIMING_REASONS}
    for row, (bit, name) in enumerate(sorted(names_by_bit.items())):
        t, failing = _thin(log.decision.t, (log.decision.reasons.astype(int) & bit) != 0)
        ax_reasons.fill_between(t, row - 0.35, row + 0.35, where=failing > 0, step="post",
                                color=colour("HA"), lw=0)
    ax_reasons.set_yticks(range(len(names_by_bit)), [n for _, n in sorted(names_by_bit.items())],
                          fontsize=8)
    ax_reasons.set_ylim(-0.6, len(names_by_bit) - 0.4)
    ax_reasons.set_title("timing and link checks failing (REASON_*)", fontsize=9)

    timeout_ms = limits["decision"]["no_command_timeout_s"] * 1000.0
    period_ms = 1000.0 / limits["decision"]["rate_hz"]
    age = command_age_s(log, lead_s=period_ms / 1000.0)
    if age is not None:
        ax_age.plot(*_thin(age[0], age[1] * 1000.0), ".", ms=2,
                    label="age of the HP command the HA judged (HA stamps: rosserial time sync)")
    if log.servo_op is not None and len(log.servo_op) > 1:
        ax_age.plot(*_thin(log.servo_op.t[1:], np.diff(log.servo_op.stamp) * 1000.0), ".", ms=2,
                    label="HP command period")
    ax_age.axhline(period_ms, color="0.4", lw=0.8, ls=":", label="HA period %g ms" % period_ms)
    ax_age.axhline(timeout_ms, color="r", lw=1.0, label="no-command timeout %g ms" % timeout_ms)
    ax_age.set_yscale("log")  # a crash's seconds and a period's milliseconds on one axis
    ax_age.set_ylabel("[ms]")
    ax_age.legend(loc="upper right", fontsize=8)
    return _save(fig, out_dir, "link_timing.png")


def command_age_s(log, lead_s=0.0):
    """(t, age): for each decision, how old the HP command it judged (last_seq) was, from the
    command's stamp to the decision's. The command is the latest one with that sequence number
    logged by then (a restarted HP counts afresh). The HA's stamps come through rosserial's time
    sync, which can put a decision up to lead_s (one HA period) before the command it judged; a
    command that recent is looked for too, or a restarted HP's seq would match its predecessor's.
    None without /servo_op."""
    if log.servo_op is None:
        return None
    op_t, op_seq, op_stamp = log.servo_op.t, log.servo_op.seq.astype(np.int64), log.servo_op.stamp
    stamp_of_seq = {}
    j = 0
    t_out, age_out = [], []
    for t, seq, stamp in zip(log.decision.t, log.decision.last_seq.astype(np.int64), log.decision.stamp):
        while j < len(op_t) and op_t[j] <= t + lead_s:
            stamp_of_seq[int(op_seq[j])] = op_stamp[j]
            j += 1
        if int(seq) in stamp_of_seq:
            t_out.append(t)
            age_out.append(stamp - stamp_of_seq[int(seq)])
    return np.array(t_out), np.array(age_out)
