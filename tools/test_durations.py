#!/usr/bin/env python3
"""Writes tools/test_durations.json from a make test run's JUnit file (.build/ws/build/
test_results/drone_ros/pytest.xml): each Python test file's seconds (its tests' setup, call and
teardown) and number of tests. conftest.py's scheduler hands the longest work out first.

    tools/test_durations.py [PYTEST_XML]"""
import collections
import json
import os
import sys
import xml.etree.ElementTree as ET

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))


def main(argv):
    xml = argv[1] if len(argv) > 1 else os.path.join(ROOT, ".build", "ws", "build", "test_results", "drone_ros",
                                                     "pytest.xml")
    seconds, tests = collections.Counter(), collections.Counter()
    for case in ET.parse(xml).iter("testcase"):
        path = case.get("classname").replace(".", "/") + ".py"
        if os.path.exists(os.path.join(ROOT, path)):
            seconds[path] += float(case.get("time") or 0.0)
            tests[path] += 1
    table = {p: {"s": round(seconds[p], 1), "tests": tests[p]} for p in sorted(seconds)}
    with open(os.path.join(ROOT, "tools", "test_durations.json"), "w") as f:
        json.dump(table, f, indent=1, sort_keys=True)
        f.write("\n")
    print("tools/test_durations.json: %d files, %.0f s" % (len(table), sum(seconds.values())))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
