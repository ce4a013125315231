#!/usr/bin/env bash
# `make check-user-ws`: what README "Building inside your own catkin workspace" promises, done the
# user's way. A fresh clone of this repository's HEAD goes into a new workspace's src/, `make
# deps` runs in it, and plain `catkin_make` builds the workspace from a clean login environment
# (no workspace sourced, no venv or pyenv on PATH, nothing from this checkout's .build). Then
# every node the launch files start must be there. Leaves nothing behind unless KEEP=1.
# usage: check_user_workspace.sh [WORKSPACE_DIR]   (default: a new folder under /tmp)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
# shellcheck source=tools/fresh_clone_workspace.sh
source "$root/tools/fresh_clone_workspace.sh"
new_workspace check-user-ws user "${1:-}"

start=$(date +%s)
(cd "$ws/src/drone_ros" && "${login_env[@]}" make deps)
deps_s=$(( $(date +%s) - start ))
build_workspace check-user-ws -j2

# The executables the launch files start (<node pkg="drone_ros" type="...">), built into devel/.
mapfile -t types < <(cd "$root" && git ls-files '*.launch' | grep -v '/test/' | xargs cat | tr '\n' ' ' \
  | grep -o '<node [^>]*>' | grep 'pkg="drone_ros"' | sed 's/.* type="\([^"]*\)".*/\1/' | sort -u)
# A launch file that takes the aircraft starts controller_$(arg aircraft): plain catkin_make builds
# it for the default aircraft (CMakeLists.txt's drone_ros_AIRCRAFT).
aircraft=$(sed -n 's/^set(${PROJECT_NAME}_AIRCRAFT "\([^"]*\)".*/\1/p' "$root/CMakeLists.txt")
[ -n "$aircraft" ] || { echo "check-user-ws: no default aircraft found in CMakeLists.txt"; exit 1; }
missing=0
for t in "${types[@]}"; do
  t=${t//\$(arg aircraft)/$aircraft}
  if [ ! -x "$ws/devel/lib/drone_ros/$t" ]; then
    echo "check-user-ws: $t (a launch file starts it) was not built into $ws/devel/lib/drone_ros"
    missing=1
  fi
done
[ $missing -eq 0 ] || exit 1
echo "check-user-ws: plain catkin_make built ${#types[@]} launch-file executables (${types[*]}); make deps ${deps_s} s, catkin_make ${build_s} s"
