#!/usr/bin/env bash
# Runs every test of the package (catkin gtests, rostests, Python tests), then prints one
# summary line over all of them and exits non-zero on any failure. Expects the workspace sourced.
set -uo pipefail
ws=$1
venv=$2
root=$(cd "$(dirname "$0")/.." && pwd)
results=$ws/build/test_results
rm -rf "$results"
mkdir -p "$results/drone_ros"

status=0
# Python tests find the built executables through this.
export DRONE_ROS_WS=$ws
# Two jobs a core: most rostests wait on their nodes (a master, a launch, a rate measured over
# seconds), so four at a time on two cores take 41 s where two took 58 s.
(cd "$ws" && catkin_make run_tests -j$((2 * $(nproc))) > "$ws/../run_tests.log" 2>&1) || status=1
grep -E '^\[ *(FAILED|  PASSED|  OK) *\]|FAILURE|ERROR:' "$ws/../run_tests.log" | grep -vE '^\[ +OK \]' | tail -n 40

mapfile -t pytest_dirs < <(cd "$root" && for d in test */test */*/test; do [ -d "$d" ] && ls "$d"/test_*.py >/dev/null 2>&1 && echo "$root/$d"; done)
# On three workers (pytest-xdist; TEST_WORKERS=1 runs them in this process, one after another):
# every flight, master and ground station of a test takes its own free ports, ptys and folders,
# so independent tests run side by side; the tests of a module sharing a module-scoped fixture
# stay on one worker (conftest.py), so a flight read by many tests is still flown once. Three on
# two cores: a worker whose test waits (a ground station's timeout, a QEMU boot, a build) leaves
# a core to the third; the 558 tests took 400 s on three, 440 s on two (one clone, back to back).
workers=${TEST_WORKERS:-3}
parallel=()
[ "$workers" -gt 1 ] && parallel=(-n "$workers" --dist loadgroup)
# Then the flights on the wall clock (the realtime mark, conftest.py), one after another with
# nothing else running: they judge deadlines, and whatever runs beside them takes the CPU their
# HP needs to be on time. Side by side (three workers) they took 25 s instead of 64 s on a fast
# machine, where a real-time flight keeps a third of a core busy; on one 3.5x slower (2026-12-07)
# the HP beside two others was late before the crash in three flights of three, and CI failed.
realtime_parallel=(-p no:xdist)
if [ ${#pytest_dirs[@]} -gt 0 ]; then
  "$venv/bin/python" -m pytest -q -p no:cacheprovider "${parallel[@]}" --durations=25 -m "not realtime" \
    --junitxml="$results/drone_ros/pytest.xml" "${pytest_dirs[@]}" || status=1
  "$venv/bin/python" -m pytest -q -p no:cacheprovider "${realtime_parallel[@]}" --durations=5 -m realtime \
    --junitxml="$results/drone_ros/pytest_realtime.xml" "${pytest_dirs[@]}" || status=1
fi

"$venv/bin/python" "$root/tools/summarize_results.py" "$results" || status=1
exit $status
