#!/usr/bin/env bash
# make pil-image: the HA firmware (src/firmware, the core, the link, the VN-200 feed, and the ground
# floor of common/: geodesy, the HP command's CRC, the VN-200 protocol) on the QEMU mps2-an385
# board of pil_main.c, as Cortex-M3 machine code: Debian's arm-none-eabi-gcc, newlib-nano, -Wall
# -Wextra -Werror, the benchmark's startup and memory map (../bench/startup_m3.c, mps2_an385.ld:
# written for this project, no vendor SDK). Prints flash, RAM and the largest stack frame as
# metric lines.
# usage: build_pil_image.sh [out_dir]     (the image: <out_dir>/ha_pil.elf)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
ha=$(cd "$here/.." && pwd)
root=$(cd "$ha/.." && pwd)
out=${1:-$root/.build/pil}
cc=arm-none-eabi-gcc
if ! command -v "$cc" > /dev/null; then
  echo "build_pil_image: $cc not found; run 'make deps' (arduino_ha/apt-packages.txt)" >&2
  exit 2
fi
rm -rf "$out"
mkdir -p "$out/obj"
# The link's message code, generated as the sketch gets it (tools/assemble_sketch.sh).
sketch=$(bash "$ha/tools/assemble_sketch.sh" "$out/sketch")
gen=$sketch/src/link/generated

m3_cflags=(-mcpu=cortex-m3 -mthumb -Os -std=c99 -ffunction-sections -fdata-sections -fstack-usage
  -Wall -Wextra -Werror -pedantic -I"$ha/src/core" -I"$ha/src/firmware" -I"$ha/src/link" -I"$ha/src/vn200"
  -I"$root/common/src" -I"$root/common/vn200" -I"$root/common/link" -I"$ha/bench" -DHA_LINK_GENERATED_HEADER="\"$gen/ha_msgs.h\""
  -DHA_AIRCRAFT_CONFIG_HEADER="\"$sketch/src/generated/aircraft_config.h\"" ${PIL_CFLAGS:-})
sources=("$ha"/src/core/*.c "$ha"/src/firmware/*.c "$ha"/src/link/*.c "$gen"/*.c
  "$ha"/src/vn200/*.c "$root"/common/vn200/*.c "$root"/common/src/{geo_wgs84,hp_command}.c
  "$ha"/src/hil/*.c "$here"/*.c
  "$ha/bench/startup_m3.c" "$ha/bench/semihost.c" "$ha/bench/insn_timer.c")
# shellcheck source=../verify/m3_lib.sh
source "$ha/verify/m3_lib.sh"
m3_objects=()
m3_compile "$out/obj" "${sources[@]}"
elf=$out/ha_pil.elf
"$cc" -mcpu=cortex-m3 -mthumb -nostartfiles --specs=nano.specs -Wl,--gc-sections \
  -Wl,-Map="$out/ha_pil.map" -T "$ha/bench/mps2_an385.ld" "${m3_objects[@]}" -lm -lc -lgcc -o "$elf"
read -r text data bss < <(m3_sizes "$elf")
frame=$(cat "$out"/obj/*.su | awk -F'\t' '$2 + 0 > m { m = $2 + 0; f = $1 } END { print m, f }')
echo "metric: pil_image_flash $((text + data)) bytes"
echo "metric: pil_image_ram $((data + bss)) bytes"
echo "metric: pil_largest_stack_frame ${frame%% *} bytes (${frame#* })"
echo "build_pil_image: $elf"
