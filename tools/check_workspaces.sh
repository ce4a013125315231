#!/usr/bin/env bash
# `make check-workspaces` (CI): `make check-user-ws` and `make check-install` on one fresh clone.
# The user's workspace is built with plain catkin_make and checked, then its user runs
# `catkin_make install` in it and the install space is checked: one full build instead of two
# (each took 131 s on the slow CI machine). Leaves nothing behind unless KEEP=1.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
ws=$(mktemp -d /tmp/drone_ros_user_ws.XXXXXX)
if [ -z "${KEEP:-}" ]; then trap 'rm -rf "$ws"' EXIT; fi
KEEP=1 "$root/tools/check_user_workspace.sh" "$ws"
KEEP=1 "$root/tools/check_install_space.sh" --in "$ws"
