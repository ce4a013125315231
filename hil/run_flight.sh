#!/usr/bin/env bash
# `make run`: flies the thesis's case study in lockstep (hil/run_flight.py; `make run
# ARGS="--realtime"` flies it in real time for QGroundControl on UDP 14550). tools/run_main.sh
# calls this with the workspace sourced and the venv first on PATH.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
shift || true  # the workspace path tools/run_main.sh passes
# make run's own options (the build's --aircraft) first, so ARGS may still override them.
exec python3 "$here/run_flight.py" "$@" ${ARGS:-}  # the venv first on PATH (cmake/python.cmake)
