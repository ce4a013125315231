#!/usr/bin/env bash
# `make check-install`: the install space flies without the source tree (README "Install space").
# As `make check-user-ws` does, a fresh clone of this repository's HEAD goes into a new
# workspace's src/ and plain catkin_make builds it from a clean login environment; here it is
# `catkin_make install` into the workspace's install/. Then the source tree, build/ and devel/ are
# moved aside, install/setup.bash alone is sourced, and the flight launch must resolve from the
# install: `roslaunch --files` (which also runs check_config.launch's checker) lists only files
# under install/, every node of `roslaunch --nodes` starts an executable under install/, and the
# installed check_config.py (with install/setup.bash sourced) accepts the installed aircraft.
# Leaves nothing behind unless KEEP=1.
# usage: check_install_space.sh [WORKSPACE_DIR]   (default: a new folder under /tmp)
#        check_install_space.sh --in WORKSPACE_DIR  (a workspace `make check-user-ws` built and
#                                                   kept: its user runs `catkin_make install`)
# JOBS (default 2) is catkin_make's -j. mavgen (a build step, not needed at run time) runs with
# this checkout's .venv Python when it has one, else `make deps` makes the clone's.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
# shellcheck source=tools/fresh_clone_workspace.sh
source "$root/tools/fresh_clone_workspace.sh"
if [ "${1:-}" = --in ]; then
  # The user's workspace as check_user_workspace.sh left it (its clone's make deps made the venv):
  # installed with its own configuration, the caller removes it.
  ws=$2
  [ -f "$ws/devel/setup.bash" ] || { echo "check-install: $ws is not a built workspace"; exit 1; }
  mavgen_python=$ws/src/drone_ros/.venv/bin/python
  build_workspace check-install -j"${JOBS:-2}" install
else
  new_workspace check-install install "${1:-}"
  mavgen_python=${DRONE_ROS_PYMAVLINK_PYTHON:-$root/.venv/bin/python}
  if [ ! -x "$mavgen_python" ]; then
    (cd "$ws/src/drone_ros" && "${login_env[@]}" make deps)
    mavgen_python=$ws/src/drone_ros/.venv/bin/python
  fi
  build_workspace check-install -j"${JOBS:-2}" -DPYTHON_EXECUTABLE=/usr/bin/python3 \
    -Ddrone_ros_PYMAVLINK_PYTHON="$mavgen_python" -DCATKIN_ENABLE_TESTING=OFF \
    -DCMAKE_INSTALL_PREFIX="$ws/install" install
fi

# Nothing but the install space from here on: the sources, build and devel spaces are moved away.
mkdir "$ws/aside"
mv "$ws/src" "$ws/build" "$ws/devel" "$ws/aside/"
share=$ws/install/share/drone_ros
mavgen_python=${mavgen_python/#$ws\/src/$ws/aside/src}  # the clone's .venv, if make deps made it, moved too
in_install() {  # "${login_env[@]}" with only install/setup.bash sourced; logs go to the workspace
  (cd "$ws" && "${login_env[@]}" ROS_HOME="$ws/ros_home" bash -c "source '$ws/install/setup.bash' && $1")
}
failed=0
fail() { echo "check-install: $*"; failed=1; }

pkg=$(in_install "rospack find drone_ros")
[ "$pkg" = "$share" ] || fail "rospack finds drone_ros at $pkg, not in the install space ($share)"

in_install "'$share/tools/check_config.py' '$share/aircraft/DG808'" > "$ws/check_config.out" \
  || fail "the installed check_config.py refuses the installed DG808 ($(cat "$ws/check_config.out"))"

# Each launch with its arguments; the HiL's three HAs (the SIL, QEMU, a real Due) start different
# programs, each of which must be installed.
for run in "DG808_flight.launch" "check_config.launch aircraft:=DG808" "DG808_hil.launch" \
  "DG808_hil.launch ha:=qemu" "DG808_hil.launch ha:=due mode:=realtime"; do
  read -r launch argline <<< "$run"
  read -r -a args <<< "${argline:-}"
  if ! files=$(in_install "roslaunch --files drone_ros $launch ${args[*]}" 2> "$ws/roslaunch.err"); then
    fail "roslaunch --files drone_ros $launch fails from the install: $(cat "$ws/roslaunch.err")"
    continue
  fi
  n=0
  for f in $files; do
    n=$((n + 1))
    case "$f" in "$ws/install/"*) ;; *) fail "$launch reads $f, outside the install space" ;; esac
    [ -f "$f" ] || fail "$launch reads $f, which is not there"
  done
  nodes=$(in_install "roslaunch --nodes drone_ros $launch ${args[*]}")
  k=0
  for node in $nodes; do
    k=$((k + 1))
    cmd=$(in_install "roslaunch --args $node drone_ros $launch ${args[*]}")
    exe=${cmd%% *}
    case "$exe" in
      "$ws/install/"*) [ -x "$exe" ] || fail "$launch: $node's $exe is not an executable" ;;
      /usr/*) ;;  # a node of a Debian ROS package (rosbag record)
      *) fail "$launch: $node starts $exe, outside the install space" ;;
    esac
  done
  echo "check-install: $launch ${args[*]} resolves from the install: $n files, $k nodes ($(echo $nodes | tr '\n' ' '))"
done
# setup.py's packages import from the install's dist-packages with / as the folder, with the
# install's ROS messages, under the venv (the simulator's jsbsim); their data is share/drone_ros;
# stack_common's C is the install's lib/libstack_common.so.
in_install "cd / && '$mavgen_python' -c \"import hil.sim, drone_ros.msg, report_core.flight_log, \
supervisor_core.node_query, vn200_sim.vn200_encode, stack_tools.paths as paths; \
from stack_common import geo; \
assert 360.0 < geo.Ref(45.0, 7.0).north_east_ft(45.001, 7.0)[0] < 370.0; \
assert hil.sim.__file__.startswith('$ws/install/lib/'), hil.sim.__file__; \
assert drone_ros.msg.__file__.startswith('$ws/install/'), drone_ros.msg.__file__; \
assert paths.ROOT == '$share', paths.ROOT\"" \
  || fail "setup.py's packages (hil.sim, report_core, ...) do not import from the install space"
[ $failed -eq 0 ] || exit 1
echo "check-install: $(cat "$ws/check_config.out"); catkin_make install ${build_s} s"
