#!/usr/bin/env bash
# Assembles the Due sketch arduino-cli compiles: arduino-cli compiles only inside the sketch
# folder (its root and src/), and the VN-200 protocol core the INS seam decodes with lives once,
# in vn200_driver/core. So the sketch is put together under OUT/arduino_ha/ (the .ino, src/ and
# src/vn200/ from vn200_driver/core), never checked in.
# usage: assemble_sketch.sh OUT   -> prints OUT/arduino_ha
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
ha=$(cd "$here/.." && pwd)
root=$(cd "$ha/.." && pwd)
out=${1:?usage: assemble_sketch.sh OUT}
sketch=$out/arduino_ha
rm -rf "$sketch"
mkdir -p "$sketch/src/vn200"
cp "$ha/arduino_ha.ino" "$sketch/"
cp -R "$ha/src/." "$sketch/src/"
cp "$root"/vn200_driver/core/*.c "$root"/vn200_driver/core/*.h "$sketch/src/vn200/"
echo "$sketch"
