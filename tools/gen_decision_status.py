#!/usr/bin/env python3
"""Writes the DecisionStatus CONTROLLER_* numbers and REASON_* bits, with their names, from
msg/DecisionStatus.msg, the one place they are defined:

  --c     the HA core's C99 header (arduino_ha/src/generated/ha_decision_status.h; checked in because
          arduino-cli compiles only the sketch folder, kept identical by
          arduino_ha/test/test_sketch_assembly.py)
  --cpp   the ground station's C++ name tables (written by CMake and microhard_gs/make.mk at build
          time, never checked in)
  --c-operator  the HA core's HA_OP_* numbers from msg/OperatorCommand.msg
          (arduino_ha/src/generated/ha_operator_command.h, checked in and kept like the first)

Every REASON_* must be one bit and every CONTROLLER_* a distinct small number counted from 0,
or the generator stops with the offending line.

usage: gen_decision_status.py --c|--cpp DECISION_STATUS_MSG OUTPUT
       gen_decision_status.py --c-operator OPERATOR_COMMAND_MSG OUTPUT
"""
import re
import sys

from stack_tools.generated_file import write_if_changed

CONSTANT = re.compile(r"^\s*(uint8|uint32)\s+(CONTROLLER|REASON)_([A-Z0-9_]+)\s*=\s*(\d+)\s*(?:#.*)?$")


def parse(path):
    controllers, reasons, errors = [], [], []
    with open(path) as f:
        for number, line in enumerate(f, 1):
            m = CONSTANT.match(line)
            if not m:
                continue
            _, kind, name, value = m.group(1), m.group(2), m.group(3), int(m.group(4))
            where = "%s:%d: %s_%s" % (path, number, kind, name)
            if kind == "REASON":
                if value == 0 or value & (value - 1) or value >= 1 << 32:
                    errors.append("%s = %d is not one bit of a uint32" % (where, value))
                reasons.append((name, value))
            else:
                controllers.append((name, value))
    if sorted(v for _, v in controllers) != list(range(len(controllers))):
        errors.append("%s: CONTROLLER_* must number 0..%d once each" % (path, len(controllers) - 1))
    if len({v for _, v in reasons}) != len(reasons):
        errors.append("%s: two REASON_* share a bit" % path)
    if not controllers or not reasons:
        errors.append("%s: no CONTROLLER_* or no REASON_* constants" % path)
    return controllers, reasons, errors


def c_header(controllers, reasons):
    width = max(len(n) for n, _ in reasons)
    lines = [
        "/* Generated from msg/DecisionStatus.msg by tools/gen_decision_status.py: edit the message,",
        " * then run `make due-sketch-msgs`. */",
        "#ifndef HA_DECISION_STATUS_H",
        "#define HA_DECISION_STATUS_H",
        "",
        "/* who drives the servos (DecisionStatus.controller) */",
        "enum {",
    ]
    lines += ["  HA_CONTROLLER_%s = %d%s" % (n, v, "," if i + 1 < len(controllers) else "")
              for i, (n, v) in enumerate(sorted(controllers, key=lambda c: c[1]))]
    lines += ["};", "", "/* one bit per failed check (DecisionStatus.reasons) */"]
    lines += ["#define HA_REASON_%-*s %du" % (width, n, v) for n, v in reasons]
    lines += ["", "#endif", ""]
    return "\n".join(lines)


def cpp_header(controllers, reasons):
    by_bit = {v.bit_length() - 1: n for n, v in reasons}
    top = max(by_bit) + 1
    lines = [
        "// Generated from msg/DecisionStatus.msg by tools/gen_decision_status.py at build time.",
        "#pragma once",
        "",
        "#include <cstdint>",
        "",
        "namespace microhard_gs {",
        "",
    ]
    lines += ["constexpr uint8_t kController%s = %d;" % ("".join(w.capitalize() for w in n.split("_")), v)
              for n, v in sorted(controllers, key=lambda c: c[1])]
    lines += ["constexpr int kControllerCount = %d;" % len(controllers),
              "// Indexed by controller number.",
              "constexpr const char* kControllerNames[kControllerCount] = {%s};" %
              ", ".join('"%s"' % n for n, _ in sorted(controllers, key=lambda c: c[1])),
              "",
              "// Indexed by bit number; null where the message defines no reason.",
              "constexpr int kReasonBits = %d;" % top,
              "constexpr const char* kReasonNames[kReasonBits] = {%s};" %
              ", ".join('"%s"' % by_bit[b] if b in by_bit else "nullptr" for b in range(top)),
              "",
              "}  // namespace microhard_gs",
              ""]
    return "\n".join(lines)


OPERATOR = re.compile(r"^\s*uint8\s+([A-Z][A-Z0-9_]*)\s*=\s*(\d+)\s*(?:#.*)?$")


def operator_header(path):
    """HA_OP_* from the message's uint8 constants: distinct, 0 left for HA_OP_NONE."""
    with open(path) as f:
        ops = [(m.group(1), int(m.group(2))) for m in map(OPERATOR.match, f) if m]
    values = [v for _, v in ops]
    if not ops or 0 in values or len(set(values)) != len(values) or max(values) > 255:
        raise ValueError("%s: the commands must be distinct uint8 numbers above 0 (0 is none)" % path)
    lines = ["/* Generated from msg/OperatorCommand.msg by tools/gen_decision_status.py: edit the",
             " * message, then run `make due-sketch-msgs`. */",
             "#ifndef HA_OPERATOR_COMMAND_H", "#define HA_OPERATOR_COMMAND_H", "",
             "/* the operator's request (OperatorCommand.command) */", "enum {", "  HA_OP_NONE = 0,"]
    lines += ["  HA_OP_%s = %d%s" % (n, v, "," if i + 1 < len(ops) else "")
              for i, (n, v) in enumerate(sorted(ops, key=lambda o: o[1]))]
    lines += ["};", "", "#endif", ""]
    return "\n".join(lines)


def main(argv):
    if len(argv) != 4 or argv[1] not in ("--c", "--cpp", "--c-operator"):
        sys.stderr.write(__doc__)
        return 2
    if argv[1] == "--c-operator":
        try:
            write_if_changed(argv[3], operator_header(argv[2]))
        except ValueError as err:
            sys.stderr.write("%s\n" % err)
            return 1
        return 0
    controllers, reasons, errors = parse(argv[2])
    if errors:
        sys.stderr.write("".join(e + "\n" for e in errors))
        return 1
    text = (c_header if argv[1] == "--c" else cpp_header)(controllers, reasons)
    write_if_changed(argv[3], text)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
