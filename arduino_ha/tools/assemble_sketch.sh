#!/usr/bin/env bash
# Assembles the Due sketch arduino-cli compiles: <out>/arduino_ha/ with arduino_ha.ino, this
# folder's src/ and the VN-200 protocol core from vn200_driver/core/ in src/vn200/. arduino-cli
# compiles only what lies inside the sketch folder, so the one VN-200 core the host tests test is
# put there here, under .build/, instead of being kept as a checked-in copy.
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
echo "$sketch"
