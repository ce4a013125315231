#!/usr/bin/env bash
# `make run`: the main job, the HiL flight of the thesis's case study with its fault (the HP
# killed at t = 100 s, the HA's takeover, restart and hand-back): hil/run_flight.sh, given the
# workspace path ($1) and the Makefile's ARGS.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
exec "$root/hil/run_flight.sh" "$@"
