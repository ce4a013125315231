"""The `machine:` line every benchmark prints after its figures (CONTRIBUTING.md, Benchmarks):
host, cores, CPU model, OS, and the load average when the benchmark started, since the machines
these figures come from are shared. Benchmarks import it as stack_tools.bench_machine."""
import os
import platform


def cpu_model():
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return "unknown cpu (%s)" % platform.machine()


def machine(note=None):
    """Call before measuring: the load it reports is the load at the start. note: what else a
    reader needs to know of the setup (e.g. "ptys, no baud limit")."""
    text = "%s, %d cores, %s, %s, load %.1f at start (shared machine)" % (
        platform.node(), os.cpu_count(), cpu_model(), platform.platform(), os.getloadavg()[0])
    return text if note is None else "%s, %s" % (text, note)
