#!/usr/bin/env bash
# Cross-compiles every .c in arduino_ha/src/core, with the ground floor it runs on (common/src), for
# the Due's Cortex-M3 with the flags of the issue, links it with verify/size_main.c into an image
# laid out for the SAM3X8E's flash and SRAM, and reports flash (text+data), RAM (data+bss) and stack figures as metric lines.
# -Werror: a warning on the target compiler fails the check.
# usage: cross_size.sh [out_dir]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
ha=$(cd "$here/.." && pwd)
root=$(cd "$ha/.." && pwd)
out=${1:-$root/.build/arduino_ha_verify/m3}
core=${HA_CORE_DIR:-$ha/src/core}  # override only to try a patched copy of the core
floor=$root/common/src  # the ground floor the core runs on: geodesy, the HP command's CRC
cc=arm-none-eabi-gcc

if ! command -v "$cc" > /dev/null; then
  echo "cross_size: $cc not found; run 'make deps' (arduino_ha/apt-packages.txt)" >&2
  exit 2
fi
rm -rf "$out"
mkdir -p "$out/core" "$out/image"

cflags=(-mcpu=cortex-m3 -mthumb -Os -std=c99 -ffunction-sections -fdata-sections -fstack-usage
  -Wall -Wextra -Werror -I"$core" -I"$floor" -I"$ha/src/firmware")

mapfile -t core_sources < <(find "$core" -maxdepth 1 -name '*.c' | LC_ALL=C sort)
core_sources+=("$floor/geo_wgs84.c" "$floor/hp_command.c")
# The period around the core on a Board (src/firmware/ha_app.c): what size_main.c steps, as the
# firmware does; measured with the core for its stack and code.
core_sources+=("$ha/src/firmware/ha_app.c" "$ha/src/firmware/ha_retained.c")
# shellcheck source=m3_lib.sh
source "$here/m3_lib.sh"
m3_objects=()
m3_cflags=("${cflags[@]}" -fcallgraph-info=su)
m3_compile "$out/core" "${core_sources[@]}"
m3_cflags=("${cflags[@]}" -I"$ha/bench")
m3_compile "$out/image" "$here/size_main.c" "$ha/bench/startup_m3.c" "$ha/bench/semihost.c"
objects=("${m3_objects[@]}")

elf=$out/ha_core_m3.elf
"$cc" -mcpu=cortex-m3 -mthumb -nostartfiles --specs=nano.specs -Wl,--gc-sections \
  -Wl,-Map="$out/ha_core_m3.map" -T "$here/due_sam3x8e.ld" "${objects[@]}" -lm -lc -lgcc -o "$elf"

read -r text data bss < <(m3_sizes "$elf")
# The core's own share: its input sections kept in the image (the map lists them after the
# garbage collection; the "Discarded input sections" part before it is skipped).
core_code=$(python3 - "$out/ha_core_m3.map" "$out/core/" <<'PY'
import re, sys
text = open(sys.argv[1], encoding="utf-8").read()
text = text[text.index("Linker script and memory map"):]
pat = re.compile(r"^ \.(?:text|rodata|data)\S*\s+0x[0-9a-f]+\s+0x([0-9a-f]+)\s+(\S+\.o)$", re.M)
print(sum(int(m.group(1), 16) for m in pat.finditer(text) if m.group(2).startswith(sys.argv[2])))
PY
)
lines=$(cat "$core"/*.c "$core"/*.h "$floor"/geo_wgs84.[ch] "$floor"/hp_command.[ch] | wc -l)

echo "metric: m3_image_flash $((text + data)) bytes"
echo "metric: m3_image_ram $((data + bss)) bytes"
echo "metric: m3_core_code_and_const ${core_code} bytes"
echo "metric: core_source_lines ${lines} lines"
# What issue 25 counts: the core's own folder, without comments, contracts or blank lines.
python3 "$ha/tools/code_lines.py" core_code_lines "$ha/src/core"
python3 "$here/stack_report.py" "$out/core" ha_app_period ha_core_step
echo "cross_size: ok ($elf; flash = text+data of the linked image incl. startup and libgcc soft-float)"
