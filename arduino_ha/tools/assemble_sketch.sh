#!/usr/bin/env bash
# Assembles the Due sketch arduino-cli compiles: <out>/arduino_ha/ with arduino_ha.ino, this
# folder's src/, the ground floor from common/ (geodesy and the HP command's CRC in src/core/, the
# VN-200 protocol in src/vn200/, the link's ha_link_msgs.h in src/link/) and the link's message
# code generated from msg/ by common/link/gen in src/link/generated/. arduino-cli compiles only
# what lies inside the sketch folder and runs no generator, so the one floor and the one message
# generator the host tests test are put there here, under .build/, instead of checked-in copies.
# usage: assemble_sketch.sh <out_dir>    (prints the sketch folder it made)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
ha=$(cd "$here/.." && pwd)
root=$(cd "$ha/.." && pwd)
out=${1:?usage: assemble_sketch.sh <out_dir>}
sketch=$out/arduino_ha  # arduino-cli wants the folder named as the .ino

rm -rf "$sketch"
mkdir -p "$sketch"
cp "$ha/arduino_ha.ino" "$sketch/"
(cd "$ha" && find src -type f \( -name '*.c' -o -name '*.cpp' -o -name '*.h' \) -print0 |
  xargs -0 cp --parents -t "$sketch")
# The ground floor (common/): the geodesy and the HP command's CRC beside the core that runs on
# them, the VN-200 protocol beside the INS feed. A file of the same name in arduino_ha would hide it.
place() {  # <sketch folder> <file>...
  local dir=$sketch/$1
  shift
  mkdir -p "$dir"
  for src in "$@"; do
    if [ -e "$dir/$(basename "$src")" ]; then
      echo "assemble_sketch: arduino_ha/$1/$(basename "$src") would hide common's" >&2
      exit 1
    fi
    cp "$src" "$dir/"
  done
}
place src/core "$root"/common/src/geo_wgs84.[ch] "$root"/common/src/hp_command.[ch]
place src/vn200 "$root"/common/vn200/*.[ch]
place src/link "$root"/common/link/ha_link_msgs.h
# arduino-cli gives the sketch no include path: a header is found only beside the file that
# includes it. Each other folder that includes a floor header by name gets a one-line header
# that includes src/core's.
for header in geo_wgs84.h hp_command.h; do
  includers=$(grep -rl --include='*.[ch]' --include='*.cpp' "#include \"$header\"" "$sketch/src" || true)
  for dir in $(xargs -r -n1 dirname <<< "$includers" | LC_ALL=C sort -u); do
    if [ "$dir" != "$sketch/src/core" ]; then
      printf '/* Written by assemble_sketch.sh: the ground floor lies in src/core. */\n#include "%s"\n' \
        "$(realpath --relative-to="$dir" "$sketch/src/core/$header")" > "$dir/$header"
    fi
  done
done
# The message code, as CMake generates it for the host builds (arduino_ha/link/CMakeLists.txt),
# with ROS's Python and Debian's genmsg.
gen=$sketch/src/link/generated
if [ -e "$gen" ]; then
  echo "assemble_sketch: arduino_ha/src/link/generated/ would hide the generated message code" >&2
  exit 1
fi
# The aircraft the firmware is for (make due-image AIRCRAFT=<name>, run_flight.py --aircraft):
# its limits.yaml generated into the sketch in place of the checked-in header, which is the
# default aircraft's (test_ha_core keeps it equal to its generation) and what arduino-cli users
# compile as it is.
if [ -n "${AIRCRAFT:-}" ]; then
  python3 "$root/tools/gen_aircraft_config.py" "$root/aircraft/$AIRCRAFT/limits.yaml" \
    "$sketch/src/generated/aircraft_config.h" >&2
fi
link_gen=$root/common/link/gen
python3 "$link_gen/make_c99_msgs.py" "$gen" drone_ros="$root/msg" std_msgs=/usr/share/std_msgs/msg \
  geometry_msgs=/usr/share/geometry_msgs/msg rosserial_msgs="$link_gen/rosserial_msgs/msg" \
  -- $(cat "$link_gen/device_types.txt") >/dev/null
echo "$sketch"
