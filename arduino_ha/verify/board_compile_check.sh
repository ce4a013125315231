#!/usr/bin/env bash
# What can be checked of the Due sketch without the Arduino SAM core (not installable here), on
# the sketch as arduino-cli gets it (tools/assemble_sketch.sh: src/ plus vn200_driver/core):
#  1. the board layer and the .ino compile as C++ (-std=gnu++11, as the SAM platform builds) with
#     -Wall -Wextra -Werror against verify/arduino_shim/, stand-in headers for the SAM core, Servo
#     and Wire APIs with their real signatures; once with the host g++ and once with
#     arm-none-eabi-g++ for the Cortex-M3 (32-bit int/pointer, no exceptions, no RTTI);
#  2. every other source arduino-cli would compile for the sketch (src/core, src/link, ...)
#     compiles with arm-none-eabi-gcc -std=gnu11 (their own strict checks live elsewhere);
#  3. the AMS 5812 counts -> pressure -> airspeed arithmetic against hand-computed values;
#  4. the whole sketch linked on the host with a fake Arduino (arduino_shim/fake_arduino.cpp) and
#     run through a scripted timeline (board_host_test.cpp).
# Not checked (needs the SAM core or the board): linking against the real core and libraries,
# timing, the hardware itself. README.md lists it.
# usage: board_compile_check.sh [out_dir]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
ha=$(cd "$here/.." && pwd)
root=$(cd "$ha/.." && pwd)
out=${1:-$root/.build/arduino_ha_verify/board}
for tool in g++ gcc arm-none-eabi-g++ arm-none-eabi-gcc; do
  if ! command -v "$tool" > /dev/null; then
    echo "board_compile_check: $tool not found; run 'make deps'" >&2
    exit 2
  fi
done
rm -rf "$out"
mkdir -p "$out/host" "$out/m3"
# Everything below compiles the assembled sketch, not the source tree: the files flashed.
ha=$(bash "$ha/tools/assemble_sketch.sh" "$out/sketch")

# arduino-cli compiles the .ino as C++ after adding #include <Arduino.h>; do the same.
{ echo '#include <Arduino.h>'; echo '#line 1 "arduino_ha.ino"'; cat "$ha/arduino_ha.ino"; } \
  > "$out/arduino_ha.ino.cpp"

strict=(-Wall -Wextra -Werror -Os -I"$here/arduino_shim" -iquote "$ha")
m3=(-mcpu=cortex-m3 -mthumb -ffunction-sections -fdata-sections)
mapfile -t board_cpp < <(find "$ha/src/board_due" -name '*.cpp' | LC_ALL=C sort)
mapfile -t board_c < <(find "$ha/src/board_due" -name '*.c' | LC_ALL=C sort)
mapfile -t other_c < <(find "$ha/src" -name '*.c' -not -path "$ha/src/board_due/*" | LC_ALL=C sort)

count=0
for src in "${board_cpp[@]}" "$out/arduino_ha.ino.cpp"; do
  name=$(basename "${src%.*}")
  g++ -std=gnu++11 "${strict[@]}" -c "$src" -o "$out/host/$name.o"
  arm-none-eabi-g++ -std=gnu++11 -fno-exceptions -fno-rtti "${m3[@]}" "${strict[@]}" \
    -c "$src" -o "$out/m3/$name.o"
  count=$((count + 1))
done
for src in "${board_c[@]}"; do
  name=$(basename "${src%.*}")
  gcc -std=gnu11 "${strict[@]}" -c "$src" -o "$out/host/$name.o"
  arm-none-eabi-gcc -std=gnu11 "${m3[@]}" "${strict[@]}" -c "$src" -o "$out/m3/$name.o"
  count=$((count + 1))
done
others=0
for src in "${other_c[@]}"; do
  rel=${src#"$ha/src/"}
  arm-none-eabi-gcc -std=gnu11 "${m3[@]}" -Os -c "$src" -o "$out/m3/other_${rel//\//_}.o"
  others=$((others + 1))
done
echo "board_compile_check: $count board/sketch files compiled warning-free (host g++ and arm-none-eabi-g++), $others other sketch sources compiled for the Cortex-M3"

gcc -std=c99 -Wall -Wextra -Werror -I"$ha/src/board_due" "$here/ams5812_check.c" \
  "$ha/src/board_due/ams5812.c" -lm -o "$out/ams5812_check"
"$out/ams5812_check"

# 4. The whole sketch linked on the host against fake_arduino.cpp (an implementation of the shim
#    that records pins, servos, I2C, the watchdog) and run through a scripted timeline:
#    board_host_test.cpp. Also proves every symbol the sketch needs is defined somewhere.
mkdir -p "$out/sil"
sil_objs=()
for src in "${other_c[@]}" "${board_c[@]}"; do
  rel=${src#"$ha/src/"}
  obj=$out/sil/${rel//\//_}.o
  gcc -std=gnu11 -O1 -c "$src" -o "$obj"
  sil_objs+=("$obj")
done
for src in "${board_cpp[@]}" "$here/arduino_shim/fake_arduino.cpp" "$here/board_host_test.cpp"; do
  obj=$out/sil/$(basename "${src%.*}").o
  g++ -std=gnu++11 "${strict[@]}" -O1 -c "$src" -o "$obj"
  sil_objs+=("$obj")
done
g++ "${sil_objs[@]}" -lm -o "$out/board_host_test"
"$out/board_host_test"
