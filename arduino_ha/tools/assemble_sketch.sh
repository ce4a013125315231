#!/usr/bin/env bash
# Assembles the Due sketch arduino-cli compiles: <out>/arduino_ha/ with arduino_ha.ino, this
# folder's src/, the VN-200 protocol core from vn200_driver/core/ in src/vn200/ and the link's
# message code generated from msg/ in src/link/generated/. arduino-cli compiles only what lies
# inside the sketch folder and runs no generator, so the one VN-200 core and the one message
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
mkdir -p "$sketch/src/vn200"
for src in "$root"/vn200_driver/core/*.c "$root"/vn200_driver/core/*.h; do
  dest=$sketch/src/vn200/$(basename "$src")
  if [ -e "$dest" ]; then
    echo "assemble_sketch: arduino_ha/src/vn200/$(basename "$src") would hide vn200_driver/core's" >&2
    exit 1
  fi
  cp "$src" "$dest"
done
# The message code, as CMake generates it for the host builds (arduino_ha/link/CMakeLists.txt),
# with ROS's Python and Debian's genmsg.
gen=$sketch/src/link/generated
if [ -e "$gen" ]; then
  echo "assemble_sketch: arduino_ha/src/link/generated/ would hide the generated message code" >&2
  exit 1
fi
python3 "$ha/link/gen/make_c99_msgs.py" "$gen" drone_ros="$root/msg" std_msgs=/usr/share/std_msgs/msg \
  geometry_msgs=/usr/share/geometry_msgs/msg rosserial_msgs="$ha/link/gen/rosserial_msgs/msg" \
  -- $(cat "$ha/link/gen/device_types.txt") >/dev/null
echo "$sketch"
