"""Writing a generated file, shared by the tools/gen_*.py generators."""
import os


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
