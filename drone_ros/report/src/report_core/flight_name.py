"""Names of flight logs: <YYYY-MM-DD_HHMMSS>-<aircraft>-<mode>.bag (the HiL output folders'
pattern, hil/HIL_INTERFACES.md section 4), never reusing the name of an existing log."""
import errno
import os
import re

_WORD = re.compile(r"^[A-Za-z0-9_]+$")


def reserve(out_dir, aircraft, mode, when):
    """Creates out_dir if needed and an empty placeholder at a fresh name for this flight's bag;
    returns its path. The placeholder is created exclusively (O_EXCL), so two recorders started in
    the same second, or a clock set back, get different names and no log is ever overwritten
    (rosbag writes <name>.active and renames it onto the placeholder when it closes the bag)."""
    for what, value in (("aircraft", aircraft), ("mode", mode)):
        if not _WORD.match(value):
            raise ValueError("%s %r: letters, digits and _ only (it is part of the log's name)" % (what, value))
    os.makedirs(out_dir, exist_ok=True)
    stem = "%s-%s-%s" % (when.strftime("%Y-%m-%d_%H%M%S"), aircraft, mode)
    for n in range(1000):
        name = stem + ("" if n == 0 else "_%d" % n) + ".bag"
        path = os.path.join(out_dir, name)
        if os.path.exists(path + ".active"):
            continue
        try:
            os.close(os.open(path, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o644))
            return path
        except OSError as error:
            if error.errno != errno.EEXIST:
                raise
    raise OSError("no free name for %s in %s" % (stem, out_dir))
