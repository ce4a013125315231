"""Writing a generated file, and the command line every `GENERATOR IN OUT` shares, for the
tools/gen_*.py generators."""
import os
import sys


def write_if_changed(path, text):
    """Writes text to path (making its folder), leaving an identical file untouched so a rebuild
    does not recompile everything that includes it."""
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    if os.path.exists(path):
        with open(path) as f:
            if f.read() == text:
                return
    with open(path, "w") as f:
        f.write(text)


def run_generator(argv, usage, name, make_text, errors, write=write_if_changed):
    """main() of a generator run as `name IN OUT`: usage and exit 2 without both, "name: error"
    and exit 1 for an error of the classes in errors, else write(OUT, make_text(IN)) and exit 0."""
    if len(argv) != 3:
        sys.stderr.write(usage)
        return 2
    try:
        text = make_text(argv[1])
    except errors as err:
        sys.stderr.write("%s: %s\n" % (name, err))
        return 1
    write(argv[2], text)
    return 0
