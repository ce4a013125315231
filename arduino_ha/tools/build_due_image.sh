#!/usr/bin/env bash
# Builds the Due image the way arduino-cli builds the assembled sketch for
# arduino:sam:arduino_due_x, against the real Arduino SAM core 1.6.12, Wire and Servo: the compile,
# archive, link and objcopy recipes of the core's platform.txt with the board's build.* values from
# boards.txt, written out below. Prints metric lines (flash and RAM against the SAM3X8E's 512 KiB
# and 96 KiB, the largest stack frame) and leaves the image in <out_dir>:
#   arduino_ha.ino.elf   the linked image (symbols, for the tests and a debugger)
#   arduino_ha.ino.bin   what bossac writes to flash (objcopy -O binary, platform.txt's recipe)
#   arduino_ha.ino.map   the linker's map (with --cref)
# Where it differs from arduino-cli, on purpose:
#  - the compiler is Debian's arm-none-eabi-gcc 12 on PATH, not the 4.8.3 arduino-cli installs;
#  - the project's own files (the sketch, src/**, the VN-200 core assembled into it) build with
#    -Wall -Wextra -Werror in place of platform.txt's -w; the core and the libraries keep -w
#    (arduino-cli's default warning level): their warnings are not ours;
#  - every file is also compiled with -fstack-usage (an extra output, no change to the code) for
#    the stack figures.
# The SAM core and Servo are taken from DUE_SAM_CORE / DUE_SERVO_LIB if set, else where arduino-cli
# installs them, else from shared/vendor beside the repository (read-only: nothing is written
# there; every output goes to <out_dir>).
# usage: [JOBS=n] [DUE_EXTRA_FLAGS=...] build_due_image.sh [out_dir]    (default .build/due_image)
#   JOBS: compiles run at once (2); DUE_EXTRA_FLAGS: added to every C and C++ compile, as
#   arduino-cli's --build-property compiler.cpp.extra_flags=... (e.g. -DDUE_HP_LINK_PORT=2)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
ha=$(cd "$here/.." && pwd)
root=$(cd "$ha/.." && pwd)
out=${1:-$root/.build/due_image}
jobs_max=${JOBS:-2}
started=$(date +%s.%N)
load=$(cut -d' ' -f1 /proc/loadavg)

for tool in arm-none-eabi-gcc arm-none-eabi-g++ arm-none-eabi-ar arm-none-eabi-objcopy \
  arm-none-eabi-size arm-none-eabi-nm; do
  if ! command -v "$tool" > /dev/null; then
    echo "build_due_image: $tool not found; run 'make deps' (arduino_ha/apt-packages.txt)" >&2
    exit 2
  fi
done

# shared/vendor beside the clone; for a git worktree also beside the main checkout it belongs to;
# for a clone of a checkout on this machine (git clone . /tmp/x) also beside that checkout.
vendor_dirs=("$root/../shared/vendor")
if common=$(git -C "$root" rev-parse --path-format=absolute --git-common-dir 2> /dev/null); then
  vendor_dirs+=("$(dirname "$common")/../shared/vendor")
fi
if origin=$(git -C "$root" config --get remote.origin.url 2> /dev/null) && [ -d "$origin" ]; then
  vendor_dirs+=("$origin/../shared/vendor")
fi
first_dir_with() {  # <file that must exist inside> <candidate dir>...
  local need=$1 dir
  shift
  for dir in "$@"; do
    if [ -n "$dir" ] && [ -e "$dir/$need" ]; then
      (cd "$dir" && pwd)
      return 0
    fi
  done
  return 1
}
candidates=()
[ -n "${DUE_SAM_CORE:-}" ] && candidates+=("$DUE_SAM_CORE")
candidates+=("${HOME:-}/.arduino15/packages/arduino/hardware/sam/1.6.12")
for v in "${vendor_dirs[@]}"; do candidates+=("$v/ArduinoCore-sam"); done
if ! sam=$(first_dir_with platform.txt "${candidates[@]}"); then
  echo "build_due_image: no Arduino SAM core 1.6.12 (arduino-cli core install arduino:sam@1.6.12," >&2
  echo "  or shared/vendor/ArduinoCore-sam beside the repository, or DUE_SAM_CORE=<dir>)" >&2
  exit 2
fi
if ! grep -qx 'version=1.6.12' "$sam/platform.txt"; then
  echo "build_due_image: $sam is not the SAM core 1.6.12 ($(grep '^version=' "$sam/platform.txt"))" >&2
  exit 2
fi
candidates=()
[ -n "${DUE_SERVO_LIB:-}" ] && candidates+=("$DUE_SERVO_LIB")
candidates+=("${HOME:-}/Arduino/libraries/Servo")
for v in "${vendor_dirs[@]}"; do candidates+=("$v/Servo"); done
if ! servo=$(first_dir_with src/Servo.h "${candidates[@]}"); then
  echo "build_due_image: no Servo library (arduino-cli lib install Servo, or shared/vendor/Servo" >&2
  echo "  beside the repository, or DUE_SERVO_LIB=<dir>)" >&2
  exit 2
fi
wire=$sam/libraries/Wire
variant=$sam/variants/arduino_due_x
core=$sam/cores/arduino
system=$sam/system

rm -rf "$out"
mkdir -p "$out/build"
build=$out/build
sketch=$(bash "$ha/tools/assemble_sketch.sh" "$out")

# boards.txt, arduino_due_x: build.mcu, f_cpu, board, extra_flags with build.usb_flags; ARDUINO is
# arduino-cli's runtime.ide.version. arduino-cli strips the single quotes of build.usb_flags and
# keeps the double quotes of usb_manufacturer/usb_product, so those two are string literals.
defines=(-mcpu=cortex-m3 -mthumb -DF_CPU=84000000L -DARDUINO=10607 -DARDUINO_SAM_DUE
  -DARDUINO_ARCH_SAM -D__SAM3X8E__ -mthumb -DUSB_VID=0x2341 -DUSB_PID=0x003e -DUSBCON
  '-DUSB_MANUFACTURER="Arduino LLC"' '-DUSB_PRODUCT="Arduino Due"')
# compiler.libsam.c.flags, then {includes}: the core, the variant, the libraries the sketch
# includes. Our files see them as system headers (-isystem, searched in the same order after our
# own -I, of which there are none): the warnings -Wextra finds in them are not ours to fix.
platform_dirs=("$system/libsam" "$system/CMSIS/CMSIS/Include/" "$system/CMSIS/Device/ATMEL/"
  "$core" "$variant" "$servo/src" "$wire/src")
# compiler.c.flags / compiler.cpp.flags / compiler.S.flags without the warning level
c_flags=(-c -g -Os -std=gnu11 -ffunction-sections -fdata-sections -nostdlib
  --param max-inline-insns-single=500 -Dprintf=iprintf -MMD)
cpp_flags=(-c -g -Os -std=gnu++11 -ffunction-sections -fdata-sections -nostdlib
  -fno-threadsafe-statics --param max-inline-insns-single=500 -fno-rtti -fno-exceptions -MMD)
s_flags=(-c -g -x assembler-with-cpp -MMD)
# compiler.c.extra_flags and compiler.cpp.extra_flags (platform.local.txt's hooks, which
# arduino-cli's --build-property sets), e.g. DUE_EXTRA_FLAGS=-DDUE_HP_LINK_PORT=2.
read -r -a extra <<< "${DUE_EXTRA_FLAGS:-}"
ours=(-Wall -Wextra -Werror)
theirs=(-w)

# compile <ours|theirs> <source> <object>: recipe.{c,cpp,S}.o.pattern. On failure it leaves a
# marker, so that the jobs can run in the background and the build still fails.
compile() {
  local who=$1 src=$2 obj=$3 warn=() dir
  if [ "$who" = ours ]; then
    warn=("${ours[@]}")
    for dir in "${platform_dirs[@]}"; do warn+=(-isystem "$dir"); done
  else
    warn=("${theirs[@]}")
    for dir in "${platform_dirs[@]}"; do warn+=("-I$dir"); done
  fi
  mkdir -p "$(dirname "$obj")"
  case $src in
    *.c) arm-none-eabi-gcc "${c_flags[@]}" "${warn[@]}" -fstack-usage "${defines[@]}" "${extra[@]}" \
      "$src" -o "$obj" ;;
    *.cpp) arm-none-eabi-g++ "${cpp_flags[@]}" "${warn[@]}" -fstack-usage "${defines[@]}" \
      "${extra[@]}" "$src" -o "$obj" ;;
    *.S) arm-none-eabi-gcc "${s_flags[@]}" "${defines[@]}" "$src" -o "$obj" ;;
  esac || { echo "$src" >> "$build/FAILED"; return 1; }
}
sources_under() {  # <dir>: C, C++ and assembler files below it, as arduino-cli's recursive walk
  find "$1" -type f \( -name '*.c' -o -name '*.cpp' -o -name '*.S' \) | LC_ALL=C sort
}

# arduino-cli's sketch preprocessing: the sketch is copied into build/sketch, where the .ino
# becomes a .cpp with Arduino.h included first, beside the src/ folder it includes from.
cp -R "$sketch" "$build/sketch"
{
  echo '#include <Arduino.h>'
  echo "#line 1 \"$sketch/arduino_ha.ino\""
  cat "$sketch/arduino_ha.ino"
} > "$build/sketch/arduino_ha.ino.cpp"
rm "$build/sketch/arduino_ha.ino"

# Objects laid out as arduino-cli lays them out: sketch/, libraries/<name>/, core/ (variant apart).
units=()  # who|source|object
add_units() {  # <ours|theirs> <source dir> <object dir>
  local src
  while read -r src; do
    units+=("$1|$src|$3/${src#"$2/"}.o")
  done < <(sources_under "$2")
}
units+=("ours|$build/sketch/arduino_ha.ino.cpp|$build/sketch/arduino_ha.ino.cpp.o")
add_units ours "$build/sketch/src" "$build/sketch/src"
add_units theirs "$servo/src" "$build/libraries/Servo"
add_units theirs "$wire/src" "$build/libraries/Wire"
add_units theirs "$variant" "$build/core/variant"
add_units theirs "$core" "$build/core"

for unit in "${units[@]}"; do
  IFS='|' read -r who src obj <<< "$unit"
  while [ "$(jobs -rp | wc -l)" -ge "$jobs_max" ]; do wait -n || true; done
  compile "$who" "$src" "$obj" &
done
wait
if [ -e "$build/FAILED" ]; then
  echo "build_due_image: failed to compile:" >&2
  sed 's/^/  /' "$build/FAILED" >&2
  exit 1
fi

# recipe.ar.pattern: the core's objects (not the variant's) into core.a.
mapfile -t core_objs < <(find "$build/core" -name '*.o' -not -path "$build/core/variant/*" |
  LC_ALL=C sort)
arm-none-eabi-ar rcs "$build/core/core.a" "${core_objs[@]}"
mapfile -t link_objs < <(find "$build/sketch" "$build/libraries" "$build/core/variant" -name '*.o' |
  LC_ALL=C sort)

# recipe.c.combine.pattern, with compiler.combine.flags.
elf=$out/arduino_ha.ino.elf
bin=$out/arduino_ha.ino.bin
arm-none-eabi-gcc -mcpu=cortex-m3 -mthumb -Os -Wl,--gc-sections \
  "-T$variant/linker_scripts/gcc/flash.ld" "-Wl,-Map,$out/arduino_ha.ino.map" -o "$elf" \
  "-L$build" -Wl,--cref -Wl,--check-sections -Wl,--gc-sections -Wl,--entry=Reset_Handler \
  -Wl,--unresolved-symbols=report-all -Wl,--warn-common -Wl,--warn-section-align \
  -Wl,--start-group -u _sbrk -u link -u _close -u _fstat -u _isatty -u _lseek -u _read -u _write \
  -u _exit -u kill -u _getpid "${link_objs[@]}" "$variant/libsam_sam3x8e_gcc_rel.a" \
  "$build/core/core.a" -Wl,--end-group -lm -lgcc
# recipe.objcopy.bin.pattern
arm-none-eabi-objcopy -O binary "$elf" "$bin"

flash_max=524288 ram_max=98304
read -r flash ram < <(arm-none-eabi-size -A "$elf" | awk '
  $1 == ".text" || $1 == ".ARM.exidx" { f += $2 } $1 == ".relocate" { f += $2; r += $2 }
  $1 == ".bss" { r += $2 } END { print f + 0, r + 0 }')
bin_bytes=$(stat -c %s "$bin")
if [ "$bin_bytes" -ne "$flash" ]; then
  echo "build_due_image: the .bin holds $bin_bytes bytes but the image's flash sections $flash" >&2
  exit 1
fi
# Largest frame of the whole image's compiled code, and of the project's own files. A .su line:
# <file>:<line>:<column>:<function>\t<bytes>\t<static|dynamic|dynamic,bounded>.
frames() {  # <dir>: "<bytes>\t<function>\t<qualifier>" for every function compiled below it
  find "$1" -name '*.su' -print0 | xargs -0 cat |
    awk -F'\t' '{ sub(/^[^:]*:[0-9]+:[0-9]+:/, "", $1); print $2 "\t" $1 "\t" $3 }'
}
IFS=$'\t' read -r frame frame_fn _ < <(frames "$build" | sort -t$'\t' -k1,1nr -k2 | head -n 1)
IFS=$'\t' read -r own_frame own_fn _ < <(frames "$build/sketch" | sort -t$'\t' -k1,1nr -k2 |
  head -n 1)
dynamic=$(frames "$build/sketch" | awk -F'\t' '$3 != "static"' | wc -l)

share() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.1f", 100 * a / b }'; }
echo "metric: due_image_flash $flash bytes"
echo "metric: due_image_flash_share $(share "$flash" "$flash_max") %"
echo "metric: due_image_ram $ram bytes"
echo "metric: due_image_ram_share $(share "$ram" "$ram_max") %"
echo "metric: due_largest_stack_frame $frame bytes"
echo "metric: due_largest_stack_frame_own $own_frame bytes"
elapsed=$(awk -v s="$started" -v e="$(date +%s.%N)" 'BEGIN { printf "%.1f", e - s }')
echo "metric: due_image_build_time $elapsed s"
cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1)
echo "machine: $(uname -m), ${cpu:-unknown cpu}, $(nproc) cores, load $load at start," \
  "$jobs_max compiles at once, $(arm-none-eabi-gcc --version | head -n 1)"
echo "largest frame: $frame_fn (of all code compiled here; libsam, libc and libgcc come" \
  "prebuilt); the project's own: $own_fn"
echo "sources: SAM core $sam, Servo $servo; ${#units[@]} files compiled${DUE_EXTRA_FLAGS:+ with}" \
  "${DUE_EXTRA_FLAGS:-}" | sed 's/ *$//'
if [ "$dynamic" -ne 0 ]; then
  echo "build_due_image: $dynamic of the project's functions have a frame that is not static" >&2
  exit 1
fi
fits=MET
if [ "$flash" -gt "$flash_max" ] || [ "$ram" -gt "$ram_max" ]; then fits=EXCEEDED; fi
echo "budget: SAM3X8E flash $flash of $flash_max bytes, RAM $ram of $ram_max bytes (data+bss;" \
  "the stack grows down from the top of the rest): $fits"
[ "$fits" = MET ] || exit 1
echo "due-image: ok ($bin, $elf)"
