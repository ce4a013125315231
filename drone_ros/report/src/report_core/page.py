"""The one HTML page a person opens: what flew, who flew when, every switch, the figures."""
import html

from .figures import colour, label

_STYLE = """
body { font-family: sans-serif; margin: 1.5em; max-width: 1250px; color: #222; }
table { border-collapse: collapse; margin: 0.5em 0 1.5em; }
th, td { border: 1px solid #bbb; padding: 0.25em 0.6em; text-align: left; }
td.num { text-align: right; font-variant-numeric: tabular-nums; }
.who { display: inline-block; width: 0.8em; height: 0.8em; margin-right: 0.3em; }
figure { margin: 1em 0 2em; }
img { max-width: 100%; border: 1px solid #ddd; }
.note { color: #555; font-size: 90%; }
"""


def _who(controller):
    return ('<span class="who" style="background:%s"></span>%s'
            % (colour(controller), html.escape(label(controller))))


def render(title, facts, runs, switches, figures, notes):
    """facts: [(name, value)]; figures: [(file, caption)]; notes: [str]."""
    out = ["<!DOCTYPE html>", '<html lang="en"><head><meta charset="utf-8">',
           "<title>%s</title><style>%s</style></head><body>" % (html.escape(title), _STYLE),
           "<h1>%s</h1>" % html.escape(title), "<table>"]
    out += ["<tr><th>%s</th><td>%s</td></tr>" % (html.escape(k), html.escape(str(v))) for k, v in facts]
    out.append("</table>")
    for note in notes:
        out.append('<p class="note">%s</p>' % html.escape(note))

    out.append('<h2>Switches</h2><table id="switches"><tr><th>#</th><th>time [s]</th><th>from</th>'
               "<th>to</th><th>reasons</th><th>duration [s]</th></tr>")
    for i, s in enumerate(switches, 1):
        reasons = ", ".join(s.reasons) if s.reasons else "none"
        if s.to_controller == "HP":
            reasons += " (HP command valid for %.2f s)" % s.stable_for_s
        duration = "%.2f%s" % (s.duration_s, " (until the end of the log)" if s.until_end else "")
        out.append('<tr><td class="num">%d</td><td class="num">%.2f</td><td>%s</td><td>%s</td>'
                   '<td>%s</td><td class="num">%s</td></tr>'
                   % (i, s.t_s, _who(s.from_controller), _who(s.to_controller), html.escape(reasons),
                      duration))
    out.append("</table>")
    if not switches:
        out.append("<p>No switch: one controller flew the whole log.</p>")

    out.append("<h2>Who flew</h2><table><tr><th>controller</th><th>from [s]</th><th>to [s]</th></tr>")
    for run in runs:
        out.append('<tr><td>%s</td><td class="num">%.2f</td><td class="num">%.2f</td></tr>'
                   % (_who(run.controller), run.start_s, run.end_s))
    out.append("</table><h2>Figures</h2>")
    for file_name, caption in figures:
        out.append('<figure><img src="%s" alt="%s"><figcaption>%s</figcaption></figure>'
                   % (html.escape(file_name), html.escape(caption), html.escape(caption)))
    out.append("</body></html>")
    return "\n".join(out) + "\n"
