#!/usr/bin/env python3
"""Stack figures for the HA core from GCC's -fstack-usage (.su) and -fcallgraph-info=su (.ci).

Prints the largest single frame and, for each entry point, the deepest call chain (sum of the
frames along it) as `metric:` lines. Fails if any frame is not statically bounded (a VLA or
alloca) or if the call graph has a cycle (recursion, forbidden in the core). Calls into code
compiled elsewhere (libgcc's soft-float routines, libc) have no .ci node with a frame size and
are listed, not counted; the QEMU benchmark measures the real high-water mark including them.

usage: stack_report.py <dir with .su/.ci files> <entry> [<entry> ...]
"""
import glob
import os
import re
import sys

NODE_RE = re.compile(r'node: \{ title: "([^"]+)" label: "([^"]*)"')
EDGE_RE = re.compile(r'edge: \{ sourcename: "([^"]+)" targetname: "([^"]+)"')
FRAME_RE = re.compile(r'\\n(\d+) bytes \((static|dynamic|dynamic,bounded)\)')


def short(title):
    return title.rsplit(":", 1)[-1] if "/" in title else title


def main(argv):
    if len(argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    folder, entries = argv[1], argv[2:]
    frames = {}  # node title -> bytes, only for functions compiled here
    qualifiers = {}
    edges = {}
    for path in sorted(glob.glob(os.path.join(folder, "*.ci"))):
        with open(path, encoding="utf-8") as f:
            text = f.read()
        for title, label in NODE_RE.findall(text):
            m = FRAME_RE.search(label)
            if m:
                frames[title] = int(m.group(1))
                qualifiers[title] = m.group(2)
            edges.setdefault(title, set())
        for src, dst in EDGE_RE.findall(text):
            edges.setdefault(src, set()).add(dst)
    if not frames:
        print("stack_report: no .ci files with frame sizes in %s" % folder, file=sys.stderr)
        return 2

    failed = False
    unbounded = sorted(t for t, q in qualifiers.items() if q != "static")
    for title in unbounded:
        print("stack_report: %s has a %s frame" % (short(title), qualifiers[title]))
        failed = True

    biggest = max(frames, key=lambda t: (frames[t], t))
    print("metric: largest_stack_frame %d bytes" % frames[biggest])
    print("largest frame: %s" % short(biggest))

    depth = {}
    state = {}  # 1 visiting, 2 done
    external = set()

    def visit(node):
        # Iterative DFS so that a deep graph cannot exhaust Python's own recursion limit.
        stack = [(node, iter(sorted(edges.get(node, ()))))]
        state[node] = 1
        while stack:
            current, children = stack[-1]
            advanced = False
            for child in children:
                if child not in frames:
                    external.add(child)
                    continue
                if state.get(child) == 1:
                    raise ValueError("recursion: %s -> %s" % (short(current), short(child)))
                if state.get(child) != 2:
                    state[child] = 1
                    stack.append((child, iter(sorted(edges.get(child, ())))))
                    advanced = True
                    break
            if not advanced:
                stack.pop()
                best = 0
                for child in edges.get(current, ()):
                    if child in frames:
                        best = max(best, depth[child])
                depth[current] = frames[current] + best
                state[current] = 2

    for entry in entries:
        if entry not in frames:
            print("stack_report: entry point %s not found" % entry, file=sys.stderr)
            return 2
        try:
            if state.get(entry) != 2:
                visit(entry)
        except ValueError as err:
            print("stack_report: %s" % err)
            return 1
        print("metric: stack_depth_%s %d bytes" % (entry, depth[entry]))
    if external:
        print("not counted (compiled elsewhere): %s" % " ".join(sorted(short(e) for e in external)))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
