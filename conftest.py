"""pytest set-up shared by every Python test of the package (a helper, not a test).

The tests stop what they start the way a person does, with Ctrl-C: SIGINT to the process group
(rosmaster, rospy nodes and the microhard_gs probe close on it). A shell that runs a command in
the background without job control (`make test > log &` in a script, CI runners, nohup) starts it
with SIGINT ignored, and an ignored signal stays ignored across fork and exec: every process a
test started would ignore the stop, sit out the test's wait and be killed (20 s per microhard_gs
test module, 30 s for test_record_flight's master). Catching SIGINT here, as an interactive
Python does, hands each child the default action again (exec resets a caught signal)."""
import json
import os
import signal
import tempfile

import pytest

# Each test file's measured seconds (setup, call and teardown of all its tests) and test count:
# make test hands the longest work to its workers first (tools/test_durations.py writes it).
DURATIONS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "tools", "test_durations.json")
GROUPS = "xdist_groups"  # under $HIL_TEST_FLIGHTS: each worker's {test id: group}


def pytest_configure(config):
    # make test runs these after the rest, side by side (tools/run_tests.sh): a flight on the
    # wall clock measures deadlines, which a lockstep flight on the other worker, taking both
    # cores, moves (CI: an HP starved late into a climbing turn, a QEMU HA behind its periods).
    config.addinivalue_line("markers", "realtime: flies on the wall clock; make test runs these after the "
                                       "others, side by side")
    if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
        signal.signal(signal.SIGINT, signal.default_int_handler)
    # One folder per test run for the flights its tests share (hil/campaigns/flight.py
    # run_once_per_test_run): made by the first pytest process, inherited by its xdist workers.
    if not os.environ.get("HIL_TEST_FLIGHTS"):
        os.environ["HIL_TEST_FLIGHTS"] = tempfile.mkdtemp(prefix="hil_test_flights_")


def shares_a_module_fixture(item):
    info = getattr(item, "_fixtureinfo", None)
    if info is None:
        return False
    return any(defs and defs[-1].scope == "module"
               for defs in (info.name2fixturedefs.get(n) for n in info.names_closure))


def pytest_collection_modifyitems(config, items):
    """make test runs these tests on three workers (pytest-xdist, --dist loadgroup). A module whose
    tests share a module-scoped fixture (one flight, one master, one build read by many tests)
    goes to one worker as a whole, so that fixture is still made once per run; every other test
    goes to whichever worker is free.

    Only a worker collects, and only the controller schedules: each worker writes its groups for
    the scheduler below. xdist's own xdist_group mark does not reach its scheduler under pytest 9
    (it rewrites a test's id through an attribute pytest 9 no longer reads), so every module's
    tests were spread over both workers, each making the module's fixture (CI: the 240 s mission
    of test_mission_from_qgc flown twice, 118 + 112 s)."""
    worker = getattr(config, "workerinput", None)
    if worker is None:
        return
    groups = {item.nodeid: item.nodeid.split("::", 1)[0] for item in items if shares_a_module_fixture(item)}
    folder = os.path.join(os.environ["HIL_TEST_FLIGHTS"], GROUPS)
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, worker["workerid"] + ".json")
    with open(path + ".tmp", "w") as f:
        json.dump(groups, f)
    os.replace(path + ".tmp", path)


@pytest.hookimpl(optionalhook=True)  # a hook of xdist's, which -p no:xdist leaves out
def pytest_xdist_make_scheduler(config, log):
    """--dist loadgroup: the tests of a module sharing a module fixture are one unit of work, every
    other test a unit of its own; a free worker takes the unit with the most measured seconds left
    (tools/test_durations.json; a file not in it counts DEFAULT_S a test), so the long flights
    start first and the short tests fill the end, where the workers finish together."""
    if config.getvalue("dist") != "loadgroup":
        return None
    from xdist.scheduler import LoadScopeScheduling
    return duration_first_groups(LoadScopeScheduling)(config, log)


DEFAULT_S = 1.0


def duration_first_groups(base):
    """The scheduler, made on demand: xdist's classes are there only when it runs."""
    class Scheduling(base):
        groups = None

        def _split_scope(self, nodeid):
            if self.groups is None:
                self.groups = {}
                folder = os.path.join(os.environ["HIL_TEST_FLIGHTS"], GROUPS)
                for name in sorted(os.listdir(folder)) if os.path.isdir(folder) else ():
                    if name.endswith(".json"):
                        with open(os.path.join(folder, name)) as f:
                            self.groups.update(json.load(f))
                try:
                    with open(DURATIONS) as f:
                        self.durations = json.load(f)
                except OSError:
                    self.durations = {}
            return self.groups.get(nodeid, nodeid)

        def expected_s(self, unit):
            total = 0.0
            for nodeid in unit:
                d = self.durations.get(nodeid.split("::", 1)[0])
                total += d["s"] / d["tests"] if d else DEFAULT_S
            return total

        def _assign_work_unit(self, node):
            longest = max(self.workqueue, key=lambda scope: self.expected_s(self.workqueue[scope]))
            self.workqueue.move_to_end(longest, last=False)
            super()._assign_work_unit(node)
    return Scheduling
