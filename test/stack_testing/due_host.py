"""The Due's sketch built for the host (arduino_ha/verify/board_compile_check.sh): the HIL build
the board tests drive through a fake native USB port (due_hil_host_run) and the one emulated at
its three ports that the Due-in-the-loop flight flies (due_hil_on_ptys)."""
import os
import subprocess

from stack_tools.paths import ROOT


def build_due_host_programs(out):
    """Builds them into out (a pathlib.Path) and returns it; the build's output fails the test."""
    done = subprocess.run(["bash", os.path.join(ROOT, "arduino_ha", "verify", "board_compile_check.sh"), str(out)],
                          capture_output=True, text=True)
    assert done.returncode == 0, "board_compile_check.sh failed:\n%s\n%s" % (done.stdout, done.stderr)
    return out
