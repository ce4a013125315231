#!/usr/bin/env bash
# `make check-aircraft-folder`: an aircraft is a folder of data. A fresh clone of this repository's
# HEAD gets a new aircraft, Testbird: a copy of aircraft/DG808 with its own name, 3 % more mass and
# a 4.7 m span instead of 4.5. Its gains are designed by the one design tool, catkin_make builds
# the stack for it (-Ddrone_ros_AIRCRAFT=Testbird: its controller, its GNC header, the HA's
# limits), and it flies 60 s of its case study in the lockstep HiL with the controller killed at
# 30 s; the verdict must be ok. Then nothing but the new folder may differ in the clone's tree
# (git status): adding an aircraft takes no edit anywhere else. Then the workspace is rebuilt for
# each other aircraft of the repository, which flies its own case study (make test flies the
# default's). Leaves nothing behind unless KEEP=1.
# usage: check_aircraft_folder.sh [WORKSPACE_DIR]   (default: a new folder under /tmp)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
# shellcheck source=tools/fresh_clone_workspace.sh
source "$root/tools/fresh_clone_workspace.sh"
new_workspace check-aircraft-folder aircraft "${1:-}"
clone=$ws/src/drone_ros
venv_python=$root/.venv/bin/python  # numpy, scipy and jsbsim (make deps)
[ -x "$venv_python" ] || { echo "check-aircraft-folder: no $venv_python: run make deps"; exit 1; }

bird=$clone/aircraft/Testbird
cp -r "$clone/aircraft/DG808" "$bird"
# The copy's own name, mass and span: 9.27 kg keeps the 1 g stall within limits.yaml's 2 % of its
# 42 ft/s, so the limits need no edit.
sed -i -e 's/^aircraft: DG808$/aircraft: Testbird/' -e 's/^mass_kg: 9.0 /mass_kg: 9.27/' \
  -e 's/^  wing_span_m: 4.5 /  wing_span_m: 4.7 /' "$bird/airframe.yaml"
sed -i 's/^aircraft: DG808$/aircraft: Testbird/' "$bird/limits.yaml"
grep -q '^mass_kg: 9.27' "$bird/airframe.yaml" && grep -q '^  wing_span_m: 4.7 ' "$bird/airframe.yaml" \
  || { echo "check-aircraft-folder: airframe.yaml's mass or span line is not where this check edits it"; exit 1; }

(cd "$clone" && "${login_env[@]}" PYTHONPATH="$clone/tools" "$venv_python" drone_ros/gnc/design/design_gains.py \
  aircraft/Testbird > "$ws/design.log" 2>&1) || { cat "$ws/design.log"; echo "check-aircraft-folder: the design failed"; exit 1; }
echo "check-aircraft-folder: $(head -n 1 "$ws/design.log")"

build_workspace check-aircraft-folder -j"${JOBS:-2}" -DPYTHON_EXECUTABLE=/usr/bin/python3 \
  -Ddrone_ros_PYMAVLINK_PYTHON="$venv_python" -DCATKIN_ENABLE_TESTING=OFF -Ddrone_ros_AIRCRAFT=Testbird
[ -x "$ws/devel/lib/drone_ros/controller_Testbird" ] \
  || { echo "check-aircraft-folder: the build made no controller_Testbird"; exit 1; }

# fly AIRCRAFT SECONDS CRASH_AT: its case study in the lockstep HiL (run_flight.py) in $ws/flight-AIRCRAFT;
# sets verdict to "ok" when the flight's verdict is ok and it reached every waypoint it had time for
# (all of them in a full case study), else to why not, and reached to "N of M".
fly() {
  local name=$1 seconds=$2 crash_at=$3 flight=$ws/flight-$1
  (cd "$ws" && "${login_env[@]}" ROS_HOME="$ws/ros_home" bash -c "source '$ws/devel/setup.bash' && \
    export PATH='$root/.venv/bin':\$PATH DRONE_ROS_VENV='$root/.venv' && python3 '$clone/hil/run_flight.py' \
    --aircraft $name --duration $seconds --crash-at $crash_at --no-bag --quiet --folder '$flight'") \
    > "$ws/flight-$name.log" 2>&1 || true
  read -r verdict reached < <("$venv_python" -c "
import json, sys
s = json.load(open(sys.argv[1]))
v, m = s.get('verdict') or {}, s.get('mission') or {}
ok = v.get('ok') and s.get('aircraft') == sys.argv[2]
print('ok' if ok else 'not-ok:%s' % s.get('status'), '%s/%s' % (m.get('reached'), m.get('waypoints')))
" "$flight/summary.json" "$name" 2>/dev/null || echo "no-summary -")
  if [ "$verdict" != ok ]; then
    tail -n 30 "$ws/flight-$name.log"
    echo "check-aircraft-folder: $name's flight: $verdict"
    exit 1
  fi
}
fly Testbird 60 30

changed=$(git -C "$clone" status --porcelain --untracked-files=normal)
if [ "$changed" != "?? aircraft/Testbird/" ]; then
  echo "check-aircraft-folder: adding the aircraft changed more than its folder:"
  echo "$changed"
  exit 1
fi
echo "check-aircraft-folder: Testbird designed, built in ${build_s} s and flown 60 s (crash at 30 s): verdict ok; only aircraft/Testbird/ is new"

# Every aircraft of the repository flies its own case study (make test flies the default's): the
# workspace rebuilt for it, 240 s with the controller killed at 100 s, every waypoint reached.
for folder in "$clone"/aircraft/*/; do
  name=$(basename "$folder")
  case "$name" in DG808|Testbird|schema) continue ;; esac
  [ -f "$folder/limits.yaml" ] || continue
  build_workspace check-aircraft-folder -j"${JOBS:-2}" -Ddrone_ros_AIRCRAFT="$name"
  fly "$name" 240 100
  total=${reached#*/}
  if [ "${reached%/*}" != "$total" ] || [ "$total" = None ]; then
    echo "check-aircraft-folder: $name's case study reached $reached waypoints"
    exit 1
  fi
  echo "check-aircraft-folder: $name rebuilt in ${build_s} s and flew its case study (240 s, crash at 100 s): verdict ok, $reached waypoints"
done
