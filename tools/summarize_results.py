#!/usr/bin/env python3
"""Reads every JUnit XML under a results folder and prints one closing line:
'N passed, N failed, N skipped'. Exits 1 when anything failed or nothing ran."""
import sys
import xml.etree.ElementTree as ET
from pathlib import Path


def wrapper_only(path):
    """rostest writes a rostest-*.xml with one case for the whole launch besides the
    rosunit-*.xml with the real cases. The wrapper counts only when it fails: then it carries
    a launch failure that has no inner result."""
    return path.name.startswith("rostest-")


def count(results_dir):
    passed = failed = 0
    failures, skips = [], []
    for path in sorted(Path(results_dir).rglob("*.xml")):
        try:
            root = ET.parse(path).getroot()
        except ET.ParseError as err:
            failed += 1
            failures.append(f"{path.name}: unreadable result file ({err})")
            continue
        cases = list(root.iter("testcase"))
        # A suite that crashed before its first case reports it only on the suite element.
        if not cases and (root.get("failures", "0") != "0" or root.get("errors", "0") != "0"):
            failed += 1
            failures.append(f"{path.name}: {root.get('name', 'suite')} failed without test cases")
        for case in cases:
            name = f"{case.get('classname', '')}.{case.get('name', '')}"
            if case.find("failure") is not None or case.find("error") is not None:
                failed += 1
                failures.append(f"{path.name}: {name}")
            elif case.find("skipped") is not None:
                skip = case.find("skipped")
                skips.append(f"{path.name}: {name}: {(skip.get('message') or skip.text or 'no reason given').strip()}")
            elif wrapper_only(path):
                continue  # its cases are counted from the rosunit-*.xml of the same rostest
            else:
                passed += 1
    return passed, failed, failures, skips


def main():
    passed, failed, failures, skips = count(sys.argv[1])
    for line in skips:  # a skip is never silent: each says which test and why
        print(f"SKIPPED {line}")
    for line in failures:
        print(f"FAILED {line}")
    print(f"{passed} passed, {failed} failed, {len(skips)} skipped")
    return 0 if failed == 0 and passed > 0 else 1


if __name__ == "__main__":
    sys.exit(main())
