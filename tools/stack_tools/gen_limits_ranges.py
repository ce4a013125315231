"""The ranges of aircraft/limits_ranges.yaml, the one table of what a limits.yaml may hold for
the keys more than one component reads.

As a module: ranges() -> {"state/roll_limit_deg": (1.0, 89.0), ...} (max None: unbounded), for
tools/stack_tools/gen_aircraft_config.py.
As a script: writes the C++ header controller_<aircraft> and microhard_gs check their parameters
with (CMake runs it at build time; never checked in).

usage: python3 -m stack_tools.gen_limits_ranges LIMITS_RANGES_YAML OUTPUT_HEADER
"""
import math
import os
import sys

from stack_tools import check_config
from stack_tools.generated_file import run_generator
from stack_tools.paths import ROOT

DEFAULT_TABLE = os.path.join(ROOT, "aircraft", "limits_ranges.yaml")


class RangeError(Exception):
    pass


def ranges(path=DEFAULT_TABLE):
    # Schema first: a range for a key limits.yaml does not have (a typo) names that key.
    try:
        doc = check_config.load(path, "limits_ranges")
    except check_config.ConfigError as e:
        raise RangeError(str(e)) from None
    out = {}
    for section, keys in (doc or {}).items():
        for key, bounds in (keys or {}).items():
            where = "%s: %s/%s" % (path, section, key)
            if not isinstance(bounds, list) or len(bounds) != 2:
                raise RangeError("%s: needs [min, max]" % where)
            low, high = bounds
            if not isinstance(low, (int, float)) or isinstance(low, bool) or not math.isfinite(low):
                raise RangeError("%s: min must be a finite number" % where)
            if high is not None and (not isinstance(high, (int, float)) or high < low):
                raise RangeError("%s: max must be null or a number not below min" % where)
            out["%s/%s" % (section, key)] = (float(low), None if high is None else float(high))
    if not out:
        raise RangeError("%s: no ranges" % path)
    return out


def identifier(path):
    return "k" + "".join(w.capitalize() for w in path.replace("/", "_").split("_"))


def header(table):
    lines = ["// Generated from aircraft/limits_ranges.yaml by tools/stack_tools/gen_limits_ranges.py at build time.",
             "#pragma once",
             "",
             "#include <limits>",
             "",
             "namespace limits_ranges {",
             "",
             "// A limits.yaml key (relative to the limits namespace) and the values every component accepts.",
             "struct Range {",
             "  const char* key;",
             "  double min;",
             "  double max;",
             "};",
             ""]
    for path, (low, high) in sorted(table.items()):
        top = "std::numeric_limits<double>::infinity()" if high is None else repr(high)
        lines.append('constexpr Range %s{"%s", %r, %s};' % (identifier(path), path, low, top))
    lines += ["", "}  // namespace limits_ranges", ""]
    return "\n".join(lines)


def main(argv):
    return run_generator(argv, __doc__, "gen_limits_ranges", lambda path: header(ranges(path)),
                         (RangeError, OSError))


if __name__ == "__main__":
    sys.exit(main(sys.argv))
