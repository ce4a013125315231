#!/usr/bin/env bash
# `make test-each`: every Python test file in a pytest process of its own, one file at a time,
# in the order `make test` finds them, so a test that leans on another file's leftovers (a
# master, a port, a module-level cache) fails here. One line per file, then the totals; exits
# non-zero if any file fails alone or leaves a ROS or HiL process running. Expects the
# workspace sourced (the Makefile does it).
# usage: run_tests_each.sh WS VENV
set -uo pipefail
ws=$1
venv=$2
root=$(cd "$(dirname "$0")/.." && pwd)
export DRONE_ROS_WS=$ws
cd "$root" || exit 2
mapfile -t files < <(for d in test */test */*/test; do [ -d "$d" ] && ls "$d"/test_*.py 2> /dev/null; done)
# Processes a test may start and must stop: an executable path ending in one of these names.
leftovers() {
  pgrep -f '(^|/)(rosmaster|roslaunch|rosout|hil_sim\.py|ha_sil|controller_[A-Za-z0-9_]+|arduino|vn200|microhard_gs)( |$)' | wc -l
}
before=$(leftovers)
failed=0
passed_tests=0
start_all=$(date +%s)
for f in "${files[@]}"; do
  start=$(date +%s)
  last=$("$venv/bin/python" -m pytest -q -p no:cacheprovider "$f" 2>&1 | tail -n 1)
  rc=${PIPESTATUS[0]}
  left=$(( $(leftovers) - before ))
  n=$(echo "$last" | grep -o '[0-9]* passed' | cut -d' ' -f1)
  passed_tests=$(( passed_tests + ${n:-0} ))
  verdict=ok
  if [ "$rc" -ne 0 ] || [ "$left" -gt 0 ]; then verdict=FAILED; failed=$(( failed + 1 )); fi
  printf '%-6s %-70s %4ss  left running: %d  %s\n' "$verdict" "$f" "$(( $(date +%s) - start ))" "$left" "$last"
done
echo "test-each: $(( ${#files[@]} - failed )) of ${#files[@]} files pass alone ($passed_tests tests, $(( $(date +%s) - start_all )) s)"
[ "$failed" -eq 0 ]
