#!/usr/bin/env python3
"""The code lines of C sources: lines with something besides comments (// and /* */, ACSL
contracts included) and blanks, the measure issue 25 counts the HA core by.

usage: code_lines.py METRIC PATH...   (a PATH that is a folder counts its *.c and *.h)
prints: metric: METRIC N lines
"""
import os
import sys


def code_lines(text):
    """Lines of text holding code once comments are removed; string and character literals are
    code (a "/*" inside one opens no comment)."""
    count, i, n = 0, 0, len(text)
    line_has_code, in_block = False, False
    while i < n:
        c = text[i]
        if c == "\n":
            count += line_has_code
            line_has_code = False
            i += 1
        elif in_block:
            if text.startswith("*/", i):
                in_block = False
                i += 2
            else:
                i += 1
        elif text.startswith("/*", i):
            in_block = True
            i += 2
        elif text.startswith("//", i):
            i = text.find("\n", i) if "\n" in text[i:] else n
        elif c in "\"'":
            end = i + 1
            while end < n and text[end] != c and text[end] != "\n":
                end += 2 if text[end] == "\\" else 1
            line_has_code = True
            i = end + 1
        else:
            line_has_code = line_has_code or not c.isspace()
            i += 1
    return count + line_has_code


def sources(paths):
    for path in paths:
        if os.path.isdir(path):
            for name in sorted(os.listdir(path)):
                if name.endswith((".c", ".h")):
                    yield os.path.join(path, name)
        else:
            yield path


def main(argv):
    if len(argv) < 3:
        sys.stderr.write(__doc__)
        return 2
    total = 0
    for path in sources(argv[2:]):
        with open(path, encoding="utf-8") as f:
            total += code_lines(f.read())
    print("metric: %s %d lines" % (argv[1], total))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
