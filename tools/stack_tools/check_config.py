"""Every YAML file the stack reads, checked against its schema in aircraft/schema/ before anything
uses it: an unknown key (a typo such as state.stall_sped_ftps), a missing key or a value of the
wrong type is refused, naming the key. Values and relations between keys stay with the component
they matter to (the HA generator, controller_params.cpp, node_config.cpp, ...).

The one loader: every Python reader of these files calls load() (the HA generator, the tunables
and ranges generators, the HiL's airframe and regions, the gain design), and the launch files
that load them into ROS parameters run this script first (launch/check_config.launch, at parse
time, before any node starts).

As a module: load(path[, kind]) -> the document, validate(doc, kind[, source]); both raise
ConfigError listing every problem.
As a script: check_config.py PATH...; each PATH an aircraft folder (every .yaml in it), a single
file, or aircraft/ itself (every aircraft folder and limits_ranges.yaml). Prints what it checked
on stdout (roslaunch keeps it as the parameter's value), problems on stderr, exits 1 on any.
"""
import difflib
import json
import os
import sys

import jsonschema
import yaml

from stack_tools.paths import ROOT

SCHEMA_DIR = os.path.join(ROOT, "aircraft", "schema")
# File name -> schema kind (aircraft/schema/<kind>.schema.json). limits_ranges.yaml's schema is
# derived from limits.schema.json: a range is only for a key limits.yaml has.
KINDS = {
    "limits.yaml": "limits",
    "airframe.yaml": "airframe",
    "controller_param.yaml": "controller_param",
    "ground_station.yaml": "ground_station",
    "tunables.yaml": "tunables",
    "vn200_mount.yaml": "vn200_mount",
    "gains.yaml": "gains",
    "limits_ranges.yaml": "limits_ranges",
}


class ConfigError(ValueError):
    pass


class _UniqueKeyLoader(yaml.SafeLoader):
    """safe_load, except that a key given twice in one mapping is refused: YAML keeps the last
    silently, so an edit to the first would be a silent no-op."""


def _construct_mapping(loader, node, deep=False):
    seen = {}
    for key_node, _ in node.value:
        key = loader.construct_object(key_node, deep=deep)
        if key in seen:
            raise ConfigError("line %d: key %r given twice (first on line %d)"
                              % (key_node.start_mark.line + 1, key, seen[key]))
        seen[key] = key_node.start_mark.line + 1
    return yaml.SafeLoader.construct_mapping(loader, node, deep=deep)


_UniqueKeyLoader.add_constructor(yaml.resolver.BaseResolver.DEFAULT_MAPPING_TAG, _construct_mapping)


def schema(kind):
    if kind == "limits_ranges":
        limits = schema("limits")
        bound = {"type": "array", "minItems": 2, "maxItems": 2,
                 "items": [{"type": "number"}, {"type": ["number", "null"]}]}
        sections = {}
        for name, section in limits["properties"].items():
            if section.get("type") == "object":
                sections[name] = {"type": "object", "additionalProperties": False,
                                  "properties": {k: bound for k in section["properties"]}}
        return {"type": "object", "additionalProperties": False, "minProperties": 1,
                "properties": sections}
    path = os.path.join(SCHEMA_DIR, kind + ".schema.json")
    if not os.path.isfile(path):
        raise ConfigError("no schema for %r (%s)" % (kind, path))
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def kind_of(path):
    name = os.path.basename(path)
    if name not in KINDS:
        raise ConfigError("%s: no schema for a file of this name (known: %s)"
                          % (path, ", ".join(sorted(KINDS))))
    return KINDS[name]


def _where(error_path):
    out = ""
    for part in error_path:
        out += "[%d]" % part if isinstance(part, int) else ("." if out else "") + str(part)
    return out


def _messages(error):
    """One line per problem, each starting with the key's dotted path."""
    where = _where(error.absolute_path)
    prefix = where + "." if where else ""
    if error.validator == "additionalProperties" and isinstance(error.instance, dict):
        known = sorted(error.schema.get("properties", {}))
        out = []
        for key in sorted(set(error.instance) - set(known), key=str):
            hint = difflib.get_close_matches(str(key), known, n=1)
            out.append("%s%s: unknown key%s" % (prefix, key,
                                                " (did you mean %s?)" % hint[0] if hint else ""))
        return out
    if error.validator == "required":
        missing = [k for k in error.validator_value if k not in error.instance]
        return ["%s%s: missing" % (prefix, k) for k in missing]
    return ["%s: %s" % (where or "(top level)", error.message)]


def validate(doc, kind, source=None):
    """Raises ConfigError naming every unknown, missing or mistyped key of doc."""
    source = source or kind + ".yaml"
    validator = jsonschema.Draft7Validator(schema(kind))
    problems = []
    for error in sorted(validator.iter_errors(doc), key=lambda e: [str(p) for p in e.absolute_path]):
        problems += ["%s: %s" % (source, line) for line in _messages(error)]
    if problems:
        raise ConfigError("\n".join(problems))
    return doc


def load(path, kind=None):
    """The YAML document at path, validated against its schema (kind: from the file name)."""
    kind = kind or kind_of(path)
    try:
        with open(path, encoding="utf-8") as f:
            doc = yaml.load(f, Loader=_UniqueKeyLoader)
    except ConfigError as error:
        raise ConfigError("%s: %s" % (path, error)) from None
    except yaml.YAMLError as error:
        raise ConfigError("%s: not valid YAML: %s" % (path, error)) from None
    return validate(doc, kind, path)


def targets(path):
    """The files a command-line PATH stands for."""
    if os.path.isfile(path):
        return [path]
    if not os.path.isdir(path):
        raise ConfigError("%s: no such file or folder" % path)
    if os.path.isfile(os.path.join(path, "limits_ranges.yaml")):  # aircraft/ itself
        out = [os.path.join(path, "limits_ranges.yaml")]
        for name in sorted(os.listdir(path)):
            if os.path.isfile(os.path.join(path, name, "limits.yaml")):
                out += targets(os.path.join(path, name))
        return out
    # An aircraft folder: every YAML file in it has a schema, so a misspelt file name (a
    # limit.yaml beside limits.yaml) is refused, not ignored.
    return [os.path.join(path, n) for n in sorted(os.listdir(path)) if n.endswith((".yaml", ".yml"))]


def main(argv):
    if len(argv) < 2:
        sys.stderr.write(__doc__)
        return 2
    checked, problems = [], []
    for arg in argv[1:]:
        try:
            files = targets(arg)
        except ConfigError as error:
            problems.append(str(error))
            continue
        for path in files:
            try:
                load(path)
                checked.append(os.path.relpath(path, ROOT) if path.startswith(ROOT) else path)
            except ConfigError as error:
                problems.append(str(error))
    if problems:
        sys.stderr.write("check_config: refused (schemas: aircraft/schema/):\n  "
                         + "\n".join(problems).replace("\n", "\n  ") + "\n")
        return 1
    sys.stdout.write("valid: %s\n" % " ".join(checked))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
