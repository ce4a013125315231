"""The campaign report from its table (flights.csv): per fault class the flights and how they
ended, takeover latency p50/p99/max, unsafe commands, time outside S_x under the HA, recovery time
(fault to HP back in control) p50/p99/max, latched count and the smallest margins; three plots
(PNG, matplotlib Agg) and one HTML page with the table, the plots, and every flight that broke the
property, died or ran out of time, each with the command that replays it."""
import csv
import html
import json
import math
import os

import numpy as np

STATUSES = ("ok", "fault_not_effective", "died", "timeout")
NUMERIC = ("fault_at_s", "fault_duration_s", "unsafe_commands", "envelope_violations_under_ha_s",
           "max_sx_row_under_ha", "takeover_latency_s", "sx_inherited_from_hp_s", "sx_left_under_ha_s", "recovery_s", "min_height_agl_ft",
           "min_airspeed_margin_ftps", "mission_progress", "stalled_under_ha_s", "longest_stall_under_ha_s",
           "stalled_from_fault_s",
           "recovery_height_loss_ft", "wind_mps", "wind_from_deg", "simulated_s", "flight_duration_s", "wall_s",
           "x_real_time", "exit_code", "leftovers_killed", "seed", "flight_id")
BOOLS = ("took_effect", "ok", "broke_property", "latched", "takeover_within_one_period", "aircraft_crashed")


def read_rows(path):
    with open(path, newline="") as f:
        return [parse(r) for r in csv.DictReader(f)]


def parse(r):
    out = dict(r)
    for k in NUMERIC:
        v = r.get(k, "")
        out[k] = None if v in ("", None) else float(v)
    for k in BOOLS:
        v = r.get(k, "")
        out[k] = None if v in ("", None) else v == "True"
    return out


def pct(values, q):
    v = [x for x in values if x is not None and not math.isnan(x)]
    if not v:
        return None
    return float(np.percentile(v, q, method="inverted_cdf"))  # nearest rank: a value that occurred


def _vals(rows, key):
    return [r[key] for r in rows if r.get(key) is not None and not math.isnan(r[key])]


def class_stats(rows):
    """One dict per class, sorted by name, then "all"."""
    classes = sorted({r["fault_class"] for r in rows})
    out = []
    for cls in classes + ["all"]:
        rs = rows if cls == "all" else [r for r in rows if r["fault_class"] == cls]
        flown = [r for r in rs if r["status"] in ("ok", "fault_not_effective")]
        lat = _vals(flown, "takeover_latency_s")
        rec = _vals(flown, "recovery_s")
        env = [r["envelope_violations_under_ha_s"] for r in flown if r["envelope_violations_under_ha_s"] is not None]
        out.append({
            "class": cls, "flights": len(rs),
            **{s: sum(1 for r in rs if r["status"] == s) for s in STATUSES},
            "broke_property": sum(1 for r in rs if r["broke_property"]),
            "takeovers": len(lat),
            "takeover_p50_ms": _ms(pct(lat, 50)), "takeover_p99_ms": _ms(pct(lat, 99)),
            "takeover_max_ms": _ms(max(lat) if lat else None),
            "unsafe_commands": int(sum(r["unsafe_commands"] or 0 for r in flown)),
            # nan: the flight left S_x under the HA (the first summary does not say how long)
            "envelope_violations_under_ha_s": float(sum(env)) if env else 0.0,
            # of which the HA itself let the aircraft out (the rest: outside already at the takeover)
            "sx_left_under_ha_s": float(sum(_vals(flown, "sx_left_under_ha_s"))),
            "crashed": sum(1 for r in flown if r.get("aircraft_crashed")),
            "recovered": len(rec),
            "recovery_p50_s": pct(rec, 50), "recovery_p99_s": pct(rec, 99),
            "recovery_max_s": max(rec) if rec else None,
            "latched": sum(1 for r in flown if r["latched"]),
            "min_height_agl_ft": min(_vals(flown, "min_height_agl_ft"), default=None),
            "min_airspeed_margin_ftps": min(_vals(flown, "min_airspeed_margin_ftps"), default=None),
            # The stall on the truth: the wing past its stall alpha under the HA (0 for the
            # property), in how many flights, and the most height a recovery cost.
            "stalled_under_ha_s": float(sum(_vals(flown, "stalled_under_ha_s"))),
            "stalled_under_ha_flights": sum(1 for r in flown if (r.get("stalled_under_ha_s") or 0.0) > 0.0),
            # a gust's tick (a period or two) against a stall held
            "longest_stall_under_ha_s": max(_vals(flown, "longest_stall_under_ha_s"), default=None),
            "recovery_height_loss_max_ft": max(_vals(flown, "recovery_height_loss_ft"), default=None),
            "wind_max_mps": max(_vals(rs, "wind_mps"), default=None),
        })
    return out


def _ms(s):
    return None if s is None else s * 1000.0


COLS = [("class", "class", "%s"), ("flights", "flights", "%d"), ("ok", "ok", "%d"),
        ("fault_not_effective", "not eff.", "%d"), ("died", "died", "%d"), ("timeout", "timeout", "%d"),
        ("broke_property", "BROKE", "%d"), ("takeovers", "takeovers", "%d"),
        ("takeover_p50_ms", "tk p50 ms", "%.0f"), ("takeover_p99_ms", "tk p99 ms", "%.0f"),
        ("takeover_max_ms", "tk max ms", "%.0f"), ("unsafe_commands", "unsafe cmds", "%d"),
        ("envelope_violations_under_ha_s", "S_x out (HA) s", "%.2f"),
        ("sx_left_under_ha_s", "of it left by HA s", "%.2f"), ("crashed", "crashed", "%d"),
        ("recovered", "recovered", "%d"),
        ("recovery_p50_s", "rec p50 s", "%.2f"), ("recovery_p99_s", "rec p99 s", "%.2f"),
        ("recovery_max_s", "rec max s", "%.2f"), ("latched", "latched", "%d"),
        ("min_height_agl_ft", "min h ft", "%.0f"), ("min_airspeed_margin_ftps", "min V-Vs ft/s", "%.1f"),
        ("stalled_under_ha_s", "stalled (HA) s", "%.2f"), ("stalled_under_ha_flights", "stalled flights", "%d"),
        ("longest_stall_under_ha_s", "longest stall (HA) s", "%.2f"),
        ("recovery_height_loss_max_ft", "rec h loss max ft", "%.0f"), ("wind_max_mps", "wind max m/s", "%.1f")]


def _cell(v, fmt):
    if v is None:
        return "-"
    if isinstance(v, float) and math.isnan(v):
        return "nan"
    return fmt % v


def table_text(stats):
    head = [c[1] for c in COLS]
    body = [[_cell(s[k], f) for k, _, f in COLS] for s in stats]
    w = [max(len(h), *(len(b[i]) for b in body)) for i, h in enumerate(head)]
    lines = ["  ".join(h.rjust(w[i]) if i else h.ljust(w[i]) for i, h in enumerate(head))]
    for b in body:
        lines.append("  ".join(c.rjust(w[i]) if i else c.ljust(w[i]) for i, c in enumerate(b)))
    return "\n".join(lines)


def table_markdown(stats):
    lines = ["| " + " | ".join(c[1] for c in COLS) + " |", "|" + "---|" * len(COLS)]
    for s in stats:
        lines.append("| " + " | ".join(_cell(s[k], f) for k, _, f in COLS) + " |")
    return "\n".join(lines)


def attention(rows):
    """Flights that broke the property, then those that died, ran out of time or whose fault did
    not take effect."""
    broke = [r for r in rows if r["broke_property"]]
    other = [r for r in rows if not r["broke_property"] and r["status"] != "ok"]
    return broke, other


def plots(rows, out_dir, ha_period_s=0.01):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    classes = sorted({r["fault_class"] for r in rows})
    flown = [r for r in rows if r["status"] in ("ok", "fault_not_effective")]
    files = []
    colors = {c: plt.cm.tab20(i % 20) for i, c in enumerate(classes)}  # 17+ classes: 20 colours

    fig, ax = plt.subplots(figsize=(7, 4))
    data = [[r["takeover_latency_s"] * 1000.0 for r in flown if r["fault_class"] == c and r["takeover_latency_s"] is not None]
            for c in classes]
    if any(data):
        ax.hist([d for d in data], bins=20, stacked=True, label=classes, color=[colors[c] for c in classes])
        ax.legend(fontsize=6, ncol=2)
    ax.axvline(ha_period_s * 1000.0, color="r", ls="--", lw=1)
    ax.text(ha_period_s * 1000.0, ax.get_ylim()[1] * 0.95, " one HA period", color="r", fontsize=8, va="top")
    ax.set_xlabel("takeover latency after the deadline miss (ms)")
    ax.set_ylabel("flights")
    ax.set_title("Takeover latency (%d takeovers)" % sum(len(d) for d in data))
    files.append(_save(fig, out_dir, "takeover_latency.png"))

    fig, ax = plt.subplots(figsize=(8, 5))
    rec = [[r["recovery_s"] for r in flown if r["fault_class"] == c and r["recovery_s"] is not None] for c in classes]
    for i, d in enumerate(rec):
        if d:
            ax.boxplot([d], positions=[i], widths=0.5, showfliers=False)
            jitter = np.linspace(-0.15, 0.15, len(d)) if len(d) > 1 else [0.0]
            ax.plot(np.full(len(d), i) + jitter, d, ".", alpha=0.6, color=colors[classes[i]])
    labels = []
    for c in classes:
        n = sum(1 for r in flown if r["fault_class"] == c)
        latched = sum(1 for r in flown if r["fault_class"] == c and r["latched"])
        labels.append("%s (%d/%d%s)" % (c, sum(1 for r in flown if r["fault_class"] == c and r["recovery_s"] is not None),
                                        n, ", %d latched" % latched if latched else ""))
    ax.set_xticks(range(len(classes)))
    ax.set_xticklabels(labels, rotation=35, ha="right", fontsize=7)
    ax.set_ylabel("fault to HP back in control (s, simulated)")
    ax.set_title("Recovery time per fault class (recovered/flights, latched)")
    fig.tight_layout()
    files.append(_save(fig, out_dir, "recovery_per_class.png"))

    fig, ax = plt.subplots(figsize=(7, 4.5))
    for c in classes:
        pts = [(r["min_airspeed_margin_ftps"], r["min_height_agl_ft"]) for r in flown
               if r["fault_class"] == c and r["min_airspeed_margin_ftps"] is not None and r["min_height_agl_ft"] is not None]
        if pts:
            ax.scatter(*zip(*pts), s=14, label=c, color=colors[c])
    ax.axvline(0.0, color="r", ls="--", lw=1)
    ax.axhline(0.0, color="r", ls="--", lw=1)
    ax.set_xlabel("smallest airspeed margin above the stall (ft/s)")
    ax.set_ylabel("lowest height above home (ft)")
    ax.set_title("Envelope margins, one point per flight")
    if classes:
        ax.legend(fontsize=6, ncol=2)
    fig.tight_layout()
    files.append(_save(fig, out_dir, "envelope_margins.png"))
    return files


def _save(fig, out_dir, name):
    import matplotlib.pyplot as plt
    path = os.path.join(out_dir, name)
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path


def campaign_notes(out_dir):
    """What campaign.json (the runner's) says about the campaign, as lines for the page."""
    try:
        with open(os.path.join(out_dir, "campaign.json")) as f:
            c = json.load(f)
    except (OSError, ValueError):
        return ()
    return ("%d flights (%s s simulated each) over %s fault classes on %s, in %.0f s wall; the table: flights.csv" % (
        c["flights"], "/".join("%g" % d for d in c.get("flight_duration_s", [])) or "?",
        len(c["classes"]) if "classes" in c else "?", c.get("scheduler", "?"), c.get("wall_s", 0.0)),)


def write(rows, out_dir, title="HiL fault campaign", notes=None):
    """Writes report.html, table.md and the PNGs into out_dir/report; returns (stats, text)."""
    if notes is None:
        notes = campaign_notes(out_dir)
    rdir = os.path.join(out_dir, "report")
    os.makedirs(rdir, exist_ok=True)
    # The property is claimed inside the aircraft's design wind; beyond it, survival alone.
    within = [r for r in rows if not r.get("beyond_design_wind")]
    beyond = [r for r in rows if r.get("beyond_design_wind")]
    stats = class_stats(within)
    beyond_stats = class_stats(beyond) if beyond else []
    text = table_text(stats) + (
        "\n\nbeyond the design wind (%d flights; judged on survival: no crash, no unsafe command):\n%s"
        % (len(beyond), table_text(beyond_stats)) if beyond else "")
    broke, other = attention(rows)
    files = plots(rows, rdir)
    with open(os.path.join(rdir, "table.md"), "w") as f:
        f.write(table_markdown(stats) + "\n")
        if beyond:
            f.write("\nBeyond the design wind (judged on survival):\n\n" + table_markdown(beyond_stats) + "\n")
    esc = html.escape
    parts = ["<!doctype html><html><head><meta charset='utf-8'><title>%s</title>" % esc(title),
             "<style>body{font-family:sans-serif;margin:2em}table{border-collapse:collapse;font-size:13px}"
             "td,th{border:1px solid #bbb;padding:3px 6px;text-align:right}td:first-child,th:first-child"
             "{text-align:left}code{font-size:12px;word-break:break-all}.bad{color:#b00;font-weight:bold}</style>"
             "</head><body>", "<h1>%s</h1>" % esc(title)]
    for n in notes:
        parts.append("<p>%s</p>" % esc(n))
    for heading, table in (("Per fault class, within the design wind", stats),
                           ("Beyond the design wind (judged on survival: no crash, no unsafe command)", beyond_stats)):
        if not table:
            continue
        parts.append("<h2>%s</h2><table><tr>%s</tr>" % (esc(heading), "".join("<th>%s</th>" % esc(c[1]) for c in COLS)))
        for s in table:
            parts.append("<tr>%s</tr>" % "".join(
                "<td%s>%s</td>" % (" class='bad'" if k in ("broke_property", "unsafe_commands", "died", "timeout")
                                   and s[k] else "", esc(_cell(s[k], fmt))) for k, _, fmt in COLS))
        parts.append("</table>")
    parts.append("<p>takeover: from the deadline miss to the HA's command on the servos; recovery: "
                 "from the fault to the HP back in control (simulated time); min h: lowest height above "
                 "home; min V-Vs: smallest calibrated airspeed above the 1 g stall; S_x out (HA): time outside S_x "
                 "while the HA flew, of which left by HA: after the HA had taken over with the aircraft inside "
                 "(the rest it inherited outside from the HP).</p>")
    for path in files:
        parts.append("<h2>%s</h2><img src='%s'>" % (esc(os.path.basename(path)[:-4].replace("_", " ")),
                                                   esc(os.path.basename(path))))
    parts.append("<h2>Flights that broke the property (%d)</h2>" % len(broke))
    parts.append(_flight_list(broke) if broke else "<p>None.</p>")
    parts.append("<h2>Flights that died, ran out of time or whose fault did not take effect (%d)</h2>" % len(other))
    parts.append(_flight_list(other) if other else "<p>None.</p>")
    parts.append("</body></html>")
    with open(os.path.join(rdir, "report.html"), "w") as f:
        f.write("\n".join(parts))
    lines = [text, ""]
    lines.append("flights that broke the property: %d" % len(broke))
    for r in broke:
        lines.append("  #%d %s seed %d: %s\n    replay: %s" % (r["flight_id"], r["fault_class"], r["seed"],
                                                             _why(r), r["command"]))
    lines.append("flights that died, timed out or whose fault did not take effect: %d" % len(other))
    for r in other:
        lines.append("  #%d %s seed %d: %s: %s\n    replay: %s" % (r["flight_id"], r["fault_class"], r["seed"],
                                                                 r["status"], r.get("reason") or "", r["command"]))
    text = "\n".join(lines)
    with open(os.path.join(rdir, "report.txt"), "w") as f:
        f.write(text + "\n")
    return stats, text


def _why(r):
    why = []
    if r.get("beyond_design_wind") and r.get("aircraft_crashed"):
        why.append("crashed beyond the design wind (%s)" % r["beyond_design_wind"])
    if r["unsafe_commands"]:
        why.append("%d servo commands outside S_u" % r["unsafe_commands"])
    env = r["envelope_violations_under_ha_s"]
    if not r.get("beyond_design_wind") and (env is None or math.isnan(env) or env > 0):
        why.append("outside S_x while the HA flew (%s s, of which %s s after it had taken over inside; max row %s)" % (
            env, r.get("sx_left_under_ha_s"), r.get("max_sx_row_under_ha")))
    if not why and r["ok"] is False and not r.get("beyond_design_wind"):
        why.append("its verdict is not ok")
    return "; ".join(why)


def _flight_list(rows):
    esc = html.escape
    items = []
    for r in rows:
        what = _why(r) if r["broke_property"] else "%s: %s" % (r["status"], r.get("reason") or "")
        items.append("<li>#%d <b>%s</b> seed %d, fault at %s s: %s<br><code>%s</code></li>" % (
            r["flight_id"], esc(r["fault_class"]), r["seed"], r["fault_at_s"], esc(what), esc(r["command"] or "")))
    return "<ul>%s</ul>" % "".join(items)
