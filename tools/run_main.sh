#!/usr/bin/env bash
# The main job: the HiL flight with fault injection. Until hil/ provides it, the main job is
# the build itself, which `make run` has just done.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
if [ -x "$root/hil/run_flight.sh" ]; then
  exec "$root/hil/run_flight.sh" "$@"
fi
echo "run: workspace built in $1; the HiL flight (hil/run_flight.sh) is not part of the stack yet."
