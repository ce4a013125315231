"""pytest set-up shared by every Python test of the package (a helper, not a test).

The tests stop what they start the way a person does, with Ctrl-C: SIGINT to the process group
(rosmaster, rospy nodes and the microhard_gs probe close on it). A shell that runs a command in
the background without job control (`make test > log &` in a script, CI runners, nohup) starts it
with SIGINT ignored, and an ignored signal stays ignored across fork and exec: every process a
test started would ignore the stop, sit out the test's wait and be killed (20 s per microhard_gs
test module, 30 s for test_record_flight's master). Catching SIGINT here, as an interactive
Python does, hands each child the default action again (exec resets a caught signal)."""
import os
import signal
import tempfile


def pytest_configure(config):
    if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
        signal.signal(signal.SIGINT, signal.default_int_handler)
    # One folder per test run for the flights its tests share (hil/campaigns/flight.py
    # run_once_per_test_run): made by the first pytest process, inherited by its xdist workers.
    if not os.environ.get("HIL_TEST_FLIGHTS"):
        os.environ["HIL_TEST_FLIGHTS"] = tempfile.mkdtemp(prefix="hil_test_flights_")


def pytest_collection_modifyitems(config, items):
    """make test runs these tests on two workers (pytest-xdist, --dist loadgroup). A module whose
    tests share a module-scoped fixture (one flight, one master, one build read by many tests)
    goes to one worker as a whole, so that fixture is still made once per run; every other test
    goes to whichever worker is free."""
    if not config.pluginmanager.hasplugin("xdist"):
        return
    import pytest
    for item in items:
        info = getattr(item, "_fixtureinfo", None)
        if info is None:
            continue
        shared = any(defs and defs[-1].scope == "module"
                     for defs in (info.name2fixturedefs.get(n) for n in info.names_closure))
        if shared:
            item.add_marker(pytest.mark.xdist_group(item.module.__name__))
