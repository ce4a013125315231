#!/usr/bin/env python3
"""Instructions per function inside each ha_core_step, from a QEMU `-d in_asm,exec,nochain` log.

Used by profile_m3.sh. Each executed translation block is charged with its instruction count to
the function its first instruction lies in (library functions included: on the FPU-less Cortex-M3
the soft-float calls are most of the cost). The totals agree with the timer-based figures of
run_bench.sh to within its 40-instruction resolution; the timer's figures are the ones to quote.

usage: profile_m3.py <elf> <log>
"""
import bisect
import collections
import subprocess
import sys


def symbols(elf):
    out = subprocess.run(["arm-none-eabi-nm", "-n", "-S", elf], capture_output=True, text=True,
                         check=True).stdout
    syms = []
    for line in out.splitlines():
        parts = line.split()
        if len(parts) == 4 and parts[2] in "tTW":
            syms.append((int(parts[0], 16), max(int(parts[1], 16), 2), parts[3]))
    syms.sort()
    return syms


def main(elf, log):
    syms = symbols(elf)
    starts = [s[0] for s in syms]
    names = {}

    def function_of(addr):
        if addr not in names:
            i = bisect.bisect_right(starts, addr) - 1
            ok = i >= 0 and addr < syms[i][0] + syms[i][1]
            names[addr] = syms[i][2] if ok else "?"
        return names[addr]

    step_entry = next(s[0] for s in syms if s[2] == "ha_core_step")
    harness = {"main", "ha_insn_timer_read", "ha_bench_timeline_next"}
    tb_size = {}
    block = None
    steps = []
    current = None
    # The same instructions with each run-time library routine (soft float, libc: names that
    # begin "__") charged to the core function that called it: which code to change.
    by_caller = []
    caller = None
    with open(log, errors="replace") as f:
        for line in f:
            if line.startswith("Trace"):
                pc = int(line[line.index("[") + 1:].split("/")[1], 16)
                name = function_of(pc)
                if pc == step_entry:
                    current = collections.Counter()
                    steps.append(current)
                    by_caller.append(collections.Counter())
                elif name in harness:
                    current = None
                if current is not None:
                    current[name] += tb_size.get(pc, 0)
                    if not name.startswith("__"):
                        caller = name
                    by_caller[-1][caller] += tb_size.get(pc, 0)
            elif line.startswith("IN:"):
                block = []
            elif block is not None and line.startswith("0x"):
                block.append(int(line.split(":")[0], 16))
            elif block is not None and not line.strip():
                if block:
                    tb_size[block[0]] = len(block)
                block = None
    if not steps:
        print("profile: no ha_core_step found in the log")
        return 1
    totals = [sum(c.values()) for c in steps]
    worst = max(range(len(steps)), key=lambda i: totals[i])
    print("profile: %d steps, median %d, max %d (step %d) instructions"
          % (len(steps), sorted(totals)[len(totals) // 2], totals[worst], worst))
    print("worst step by function:")
    for name, count in steps[worst].most_common(25):
        print("  %6d  %s" % (count, name))
    print("worst step, library routines charged to their caller:")
    for name, count in by_caller[worst].most_common(25):
        print("  %6d  %s" % (count, name))
    mean = collections.Counter()
    for c in steps:
        mean.update(c)
    print("mean per step by function:")
    for name, count in mean.most_common(25):
        print("  %6.0f  %s" % (count / len(steps), name))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
