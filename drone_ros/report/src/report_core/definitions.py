"""Names of a message's constants, read from its definition text (the one a bag stores with
each connection, or the generated class's _full_text), so the report never restates a table
that msg/DecisionStatus.msg already owns."""
import re

_CONSTANT = re.compile(r"^\s*(?:u?int(?:8|16|32|64)|byte|char)\s+([A-Za-z_][A-Za-z0-9_]*)\s*=\s*(-?\d+)")


def constants(definition_text, prefix):
    """{value: NAME-without-prefix} for the integer constants named PREFIX* in the first
    (top-level) message of a definition text."""
    names = {}
    for line in definition_text.split("\n"):
        if line.startswith("=" * 10):  # the embedded definitions of dependencies follow
            break
        match = _CONSTANT.match(line.split("#", 1)[0])
        if match and match.group(1).startswith(prefix):
            names[int(match.group(2))] = match.group(1)[len(prefix):]
    return names


def bit_names(mask, names_by_bit):
    """The names of the bits set in mask, lowest bit first; bits the definition does not name
    are shown by value, so a newer firmware's reason is never dropped silently."""
    out = []
    bit = 1
    mask = int(mask)
    while mask and bit <= mask:
        if mask & bit:
            out.append(names_by_bit.get(bit, "unnamed bit 0x%x" % bit))
        bit <<= 1
    return out
