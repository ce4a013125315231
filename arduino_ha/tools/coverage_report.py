#!/usr/bin/env python3
"""Branch coverage of the HA core from gcov's JSON (gcc 12 `gcov --json-format`).

A core file compiled into several objects (a header's inline function in every object that
includes it) has each branch counted once: the branch at line L, arc k is taken if any object
took it. Prints, per file of the core with branches, `metric: branch coverage <file>: P %` with
the counts, then the whole core's figure, then every branch never taken (file:line and the
source). Fails (exit 1) when a file named in --floor, or the whole core (--total-floor), is below
its floor."""
import argparse
import gzip
import json
import os
import sys


def in_core(name, cores):
    """Whether the source `name` is one of the core's: a file of a --core folder, or a --core file."""
    return any(name == core or os.path.dirname(name) == core for core in cores)


def load(paths, cores):
    """{file: {(line, arc): taken}} for the core's files, and {file: its path}."""
    cores = [os.path.realpath(core) for core in cores]
    seen = {}
    where = {}
    for path in paths:
        with gzip.open(path, "rt") as f:
            doc = json.load(f)
        cwd = doc.get("current_working_directory", "")
        for entry in doc["files"]:
            name = os.path.realpath(os.path.join(cwd, entry["file"]))
            if not in_core(name, cores):
                continue
            where[os.path.basename(name)] = name
            arcs = seen.setdefault(os.path.basename(name), {})
            for line in entry["lines"]:
                for k, branch in enumerate(line.get("branches", [])):
                    if branch.get("throw"):
                        continue  # C has no exceptions: none in the core
                    key = (line["line_number"], k)
                    arcs[key] = arcs.get(key, False) or branch["count"] > 0
    return seen, where


def parse_floor(text):
    name, _, pct = text.partition("=")
    if not name or not pct:
        raise argparse.ArgumentTypeError("--floor wants FILE=PERCENT, got %r" % text)
    return name, float(pct)


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--core", required=True, action="append",
                    help="a folder of the core's sources, or one source (repeatable)")
    ap.add_argument("--floor", type=parse_floor, action="append", default=[],
                    help="FILE=PERCENT: fail when this core file's branch coverage is below")
    ap.add_argument("--total-floor", type=float, default=0.0, help="the whole core's floor, percent")
    ap.add_argument("json", nargs="+", help="gcov .gcov.json.gz files")
    args = ap.parse_args(argv)
    files, where = load(args.json, args.core)
    if not files:
        print("coverage-ha: no core file in gcov's output", file=sys.stderr)
        return 1
    failed = []
    total = taken_total = 0
    for name in sorted(files):
        arcs = files[name]
        if not arcs:
            continue
        taken = sum(1 for t in arcs.values() if t)
        total += len(arcs)
        taken_total += taken
        print("metric: branch coverage %s: %.1f %% (%d of %d)" % (name, 100.0 * taken / len(arcs), taken, len(arcs)))
    whole = 100.0 * taken_total / total
    print("metric: branch coverage core: %.1f %% (%d of %d)" % (whole, taken_total, total))
    for name, floor in args.floor:
        arcs = files.get(name)
        if not arcs:
            failed.append("%s: no branches seen (is it a core file?)" % name)
            continue
        pct = 100.0 * sum(1 for t in arcs.values() if t) / len(arcs)
        if pct < floor:
            failed.append("%s %.1f %% < %.1f %%" % (name, pct, floor))
    if whole < args.total_floor:
        failed.append("core %.1f %% < %.1f %%" % (whole, args.total_floor))
    print("untaken branches (file:line arc: source):")
    for name in sorted(files):
        source = []
        path = where.get(name, "")
        if os.path.exists(path):
            with open(path) as f:
                source = f.read().splitlines()
        for (line, k), taken in sorted(files[name].items()):
            if not taken:
                text = source[line - 1].strip() if 0 < line <= len(source) else ""
                print("  %s:%d arc %d: %s" % (name, line, k, text))
    if failed:
        print("coverage-ha: below the floor: " + "; ".join(failed), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
