#!/usr/bin/env bash
# `make coverage-ha`: branch coverage of the HA core (arduino_ha/src/core, with the ground floor it
# runs on: common/src/geo_wgs84.c and hp_command.c, and the period around it on a Board:
# src/firmware/ha_app.c and ha_retained.c) by the project's own
# host tests. The package is built a second time, in .build/coverage_ws, with gcc's --coverage
# at -O0 (the flight build's -O2 folds branches away); only the HA's test binaries are built and
# run: test_ha_core (stories, unit tests), test_ha_core_properties (random steps) and
# test_ha_firmware (the loop and the link's stories through it). gcov's JSON then goes to
# coverage_report.py, which prints the metric lines, lists every branch never taken, and fails
# below the floors it is given.
# usage: coverage_ha.sh ROOT [coverage_report.py args...]
set -euo pipefail
root=$1
shift
ws=$root/.build/coverage_ws
mkdir -p "$ws/src"
ln -sfn ../../.. "$ws/src/drone_ros"
touch "$root/.build/CATKIN_IGNORE"
tests=(test_ha_core test_ha_core_properties test_ha_firmware)
flags="--coverage -O0"
if ! (cd "$ws" && PATH=/usr/bin:$PATH catkin_make -j"${JOBS:-2}" -DPYTHON_EXECUTABLE=/usr/bin/python3 \
      -DCATKIN_ENABLE_TESTING=ON -DCMAKE_BUILD_TYPE=Debug -DCMAKE_C_FLAGS="$flags" \
      -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS=--coverage "${tests[@]}" \
      > "$ws/build.log" 2>&1); then
  tail -n 40 "$ws/build.log"
  echo "coverage-ha: build failed (log in $ws/build.log)"
  exit 1
fi
find "$ws/build" -name '*.gcda' -delete
for t in "${tests[@]}"; do
  if ! "$ws/devel/lib/drone_ros/$t" > "$ws/$t.log" 2>&1; then
    tail -n 20 "$ws/$t.log"
    echo "coverage-ha: $t failed (log in $ws/$t.log)"
    exit 1
  fi
done
# Each object of a core source that ran, its counts into gcov's JSON (one .gcov.json.gz each).
out=$ws/gcov
rm -rf "$out" && mkdir -p "$out"
mapfile -t gcda < <(find "$ws/build" -name '*.gcda' \( -path '*src/core/*' -o -path '*common/*' \
  -o -name 'ha_app.c.gcda' -o -name 'ha_retained.c.gcda' \))
(cd "$out" && gcov --branch-probabilities --json-format --preserve-paths "${gcda[@]}" > gcov.log 2>&1)
python3 "$root/arduino_ha/tools/coverage_report.py" --core "$root/arduino_ha/src/core" \
  --core "$root/common/src/geo_wgs84.c" --core "$root/common/src/hp_command.c" \
  --core "$root/arduino_ha/src/firmware/ha_app.c" --core "$root/arduino_ha/src/firmware/ha_retained.c" \
  "$@" "$out"/*.gcov.json.gz
