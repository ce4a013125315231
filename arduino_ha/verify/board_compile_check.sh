#!/usr/bin/env bash
# What the real Due image (tools/build_due_image.sh, `make due-image`: the assembled sketch compiled
# and linked for the Cortex-M3 against the real SAM core, Wire and Servo, with -Wall -Wextra
# -Werror on the project's files) cannot show, because it only builds: the sketch RUN. On the
# sketch as arduino-cli gets it (tools/assemble_sketch.sh: src/ plus common/vn200):
#  1. the AMS 5812 counts -> pressure -> airspeed arithmetic against hand-computed values;
#  2. the whole sketch (board layer, core, link, VN-200 seam) built for the host with -Wall
#     -Wextra -Werror on the board layer, linked with a fake Arduino (arduino_shim/: stand-in
#     headers with the SAM core's, Servo's and Wire's signatures, and fake_arduino.cpp, which
#     records pins, servos, I2C and the watchdog) and run through a scripted timeline
#     (board_host_test.cpp);
#  3. the HIL build of the sketch (HA_DUE_HIL=1) linked the same way with a fake native USB port, a
#     program test/test_due_hil_board.py drives with the simulator's own record encoders;
#  4. the same HIL build as a Due emulated at its ports (due_hil_on_ptys.cpp: three ptys, the host's
#     clock), which hil/test/test_due_flight.py flies in real time through hil/ha_due.py.
# The compiles of the board layer and of every other sketch source for the Cortex-M3 against the
# shim that used to be here are gone: the real image compiles the same files for the same CPU,
# strictly, against the real headers. Not checked here or there: timing, the hardware itself
# (README.md lists it).
# usage: board_compile_check.sh [out_dir]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
ha=$(cd "$here/.." && pwd)
root=$(cd "$ha/.." && pwd)
out=${1:-$root/.build/arduino_ha_verify/board}
for tool in g++ gcc; do
  if ! command -v "$tool" > /dev/null; then
    echo "board_compile_check: $tool not found; run 'make deps'" >&2
    exit 2
  fi
done
rm -rf "$out"
mkdir -p "$out"
# Everything below builds the assembled sketch, not the source tree: the files flashed.
ha=$(bash "$ha/tools/assemble_sketch.sh" "$out/sketch")

strict=(-Wall -Wextra -Werror -I"$here/arduino_shim" -iquote "$ha")
mapfile -t board_cpp < <(find "$ha/src/board_due" -name '*.cpp' | LC_ALL=C sort)
mapfile -t board_c < <(find "$ha/src/board_due" -name '*.c' | LC_ALL=C sort)
mapfile -t other_c < <(find "$ha/src" -name '*.c' -not -path "$ha/src/board_due/*" | LC_ALL=C sort)

# 1. The AMS 5812 arithmetic.
gcc -std=c99 -Wall -Wextra -Werror -I"$ha/src/board_due" "$here/ams5812_check.c" \
  "$ha/src/board_due/ams5812.c" -lm -o "$out/ams5812_check"
"$out/ams5812_check"

# 2. The whole sketch linked on the host against fake_arduino.cpp (an implementation of the shim
#    that records pins, servos, I2C, the watchdog) and run through a scripted timeline:
#    board_host_test.cpp.
mkdir -p "$out/sil"
c_objs=()
for src in "${other_c[@]}" "${board_c[@]}"; do
  rel=${src#"$ha/src/"}
  obj=$out/sil/${rel//\//_}.o
  gcc -std=gnu11 -O1 -c "$src" -o "$obj"
  c_objs+=("$obj")
done
# host_sketch <obj dir> <binary> <main.cpp> [flags]: the C++ half of the sketch with the shim and
# a main, linked with the C half above.
host_sketch() {
  local dir=$1 bin=$2 main=$3 src obj objs=("${c_objs[@]}")
  shift 3
  mkdir -p "$dir"
  for src in "${board_cpp[@]}" "$here/arduino_shim/fake_arduino.cpp" "$main"; do
    obj=$dir/$(basename "${src%.*}").o
    g++ -std=gnu++11 "${strict[@]}" "$@" -O1 -c "$src" -o "$obj"
    objs+=("$obj")
  done
  g++ "${objs[@]}" -lm -o "$bin"
}
host_sketch "$out/sil" "$out/board_host_test" "$here/board_host_test.cpp"
"$out/board_host_test"

# 3. The HIL build (HA_DUE_HIL=1, src/board_due/due_hil_board.h) of the same sketch with a fake
#    native USB port, as a program the simulator's record encoders drive: test/test_due_hil_board.py
#    runs it (the frames come from hil/ha_channel.py and hil/ha_qemu.py, not from C).
host_sketch "$out/hil" "$out/due_hil_host_run" "$here/due_hil_host_run.cpp" -DHA_DUE_HIL=1
echo "board_compile_check: HIL build linked on the host: $out/due_hil_host_run"

# 4. The same objects with a main that puts the Due's three ports on ptys (due_hil_on_ptys.cpp).
g++ -std=gnu++11 "${strict[@]}" -DHA_DUE_HIL=1 -O1 -c "$here/due_hil_on_ptys.cpp" -o "$out/due_hil_on_ptys.o"
mapfile -t hil_objs < <(find "$out/hil" -name '*.o' -not -name 'due_hil_host_run.o' | LC_ALL=C sort)
g++ "${c_objs[@]}" "${hil_objs[@]}" "$out/due_hil_on_ptys.o" -lutil -lm -o "$out/due_hil_on_ptys"
echo "board_compile_check: the HIL build as a Due on ptys: $out/due_hil_on_ptys"
