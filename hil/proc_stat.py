"""A process as the kernel lists it in /proc/PID/stat (proc(5)): read by the fields after the
command name, which may itself hold spaces and parentheses."""


def stat_fields(pid):
    """The fields after the command name (state, ppid, ...), or None once the process is gone."""
    try:
        with open("/proc/%s/stat" % pid) as f:
            return f.read().rsplit(")", 1)[1].split()
    except OSError:
        return None


def state(pid):
    """The state letter (R running, S sleeping, T stopped, Z zombie ...), or None once gone."""
    fields = stat_fields(pid)
    return fields[0] if fields else None


# The states of a process that runs no more: gone (None), a zombie (listed until its parent reaps
# it) or exiting.
DEAD = (None, "Z", "X")


def dead(pid):
    """It runs no more."""
    return state(pid) in DEAD
